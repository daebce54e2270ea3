"""The publications exubrush's models rest on, and which of them a run relied on.

Each run records the references its models and laws come from in run.json
(``references``, :func:`run_references`). README.md ("How to cite"), docs/model.md
("References") and CITATION.cff give the same text; tests/unit/test_references.py keeps
them equal.

The contact laws of the tip on the surface are the paper's (its eqs. 14 and 15); their
sources are entries of the paper's bibliography, cited here through the paper. The
contact between bristles is exubrush's own law, with no published source.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol


@dataclass(frozen=True)
class Reference:
    """One source: ``citation`` as text to cite, ``doi`` where the source has one that
    could be checked (None otherwise), ``used_for`` what exubrush takes from it."""

    key: str
    citation: str
    used_for: str
    doi: str | None = None

    def record(self) -> dict[str, str]:
        """The entry as run.json holds it (no ``doi`` key where there is none)."""
        entry = {"key": self.key, "citation": self.citation, "used_for": self.used_for}
        return entry if self.doi is None else {**entry, "doi": self.doi}


PAPER = Reference(
    "cellupica2024",
    "Cellupica, A., D'Angelo, L., Cirelli, M., Mazur, M., Valentini, P.P.: Flexible "
    "multibody approaches for simulating the deflection and contact mechanics of "
    "toothbrush bristles: modelling and testing. Multibody System Dynamics (2024)",
    "the PRB and DFM bristle models, the tip-surface contact and friction laws (eqs. 14, "
    "15) with the parameters of table 2, the orthogonal and parallel brushing cases",
    doi="10.1007/s11044-024-09985-1",
)
FLORES = Reference(
    "flores-penalty",
    "Flores's extension of the Hertz penalty law, as Cellupica et al. (2024) give it: "
    "their eq. 14, after their refs. [35-37]",
    "the normal force of a tip on the surface",
)
FRICTION = Reference(
    "velocity-friction",
    "The velocity-based friction law of Cellupica et al. (2024): their eq. 15, after "
    "their refs. [39-42]",
    "the friction of a tip on the surface",
)
HAESSIG_FRIEDLAND = Reference(
    "haessig1991",
    "Haessig, D.A., Friedland, B.: On the modeling and simulation of friction. Journal of "
    "Dynamic Systems, Measurement, and Control 113(3), 354-362 (1991)",
    "the stick/slip friction law's stick state: a tangential spring whose anchor is reset "
    "where the spring's force would exceed the friction limit (their reset integrator)",
)
HOWELL = Reference(
    "howell2001",
    "Howell, L.L.: Compliant Mechanisms. Wiley, New York (2001)",
    "the PRB model's characteristic pivot and stiffness, gamma and K_theta (table 5.1; "
    "the paper's table 1, its ref. [20])",
)
TIMOSHENKO_GERE = Reference(
    "timoshenko1961",
    "Timoshenko, S.P., Gere, J.M.: Theory of Elastic Stability, 2nd edn. McGraw-Hill, "
    "New York (1961)",
    "the buckling load of the PRB link, a column clamped at the root and pinned at the "
    "tip (section 2.5)",
)
BRISTLE_CONTACT = Reference(
    "exubrush-bristle-contact",
    "exubrush's own law of contact between bristles: docs/tufts.md, 'Contact between "
    "bristles' (no published source)",
    "the contact between bristles",
)

LITERATURE = (PAPER, HOWELL, TIMOSHENKO_GERE, HAESSIG_FRIEDLAND)
"""The references that are publications (the others point into the paper or the docs)."""


class _ModelChoice(Protocol):
    """A case's ``[model]``, as far as the references depend on it."""

    @property
    def kind(self) -> str: ...

    @property
    def prb_link(self) -> str: ...


class _ContactChoice(Protocol):
    """A case's ``[contact]``, as far as the references depend on it."""

    @property
    def between_bristles(self) -> bool: ...

    @property
    def friction_model(self) -> str: ...


class CaseChoices(Protocol):
    """What :func:`run_references` reads of a case (an
    :class:`exubrush.parameters.case.Case`, which sits above this module)."""

    @property
    def model(self) -> _ModelChoice: ...

    @property
    def contact(self) -> _ContactChoice: ...


def run_references(case: CaseChoices) -> list[dict[str, str]]:
    """The references a run of ``case`` relied on, as run.json records them: the paper and
    its contact laws always (every tip touches the surface), Haessig & Friedland for the
    stick/slip friction, Howell for PRB and Timoshenko & Gere for its buckling link,
    exubrush's law where bristles touch each other."""
    used = [PAPER, FLORES, FRICTION]
    if case.contact.friction_model == "stick-slip":
        used.append(HAESSIG_FRIEDLAND)
    if case.model.kind == "prb":
        used.append(HOWELL)
        if case.model.prb_link == "buckling":
            used.append(TIMOSHENKO_GERE)
    if case.contact.between_bristles:
        used.append(BRISTLE_CONTACT)
    return [reference.record() for reference in used]

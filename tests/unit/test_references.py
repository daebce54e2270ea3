"""The references: which ones a run relied on, one text everywhere they are cited
(exubrush/util/references.py, README.md, docs/model.md, CITATION.cff), and run.json readers
that do not need them."""

import json
import tomllib
from pathlib import Path

import yaml

from exubrush.output.rundir import recorded_status, run_record
from exubrush.parameters.catalogue import orthogonal_case
from exubrush.util.references import (
    BRISTLE_CONTACT,
    FLORES,
    FRICTION,
    HAESSIG_FRIEDLAND,
    HOWELL,
    LITERATURE,
    PAPER,
    TIMOSHENKO_GERE,
    Reference,
    run_references,
)

ROOT = Path(__file__).parents[2]


def _keys(case):
    return [entry["key"] for entry in run_references(case)]


def _flat(text):
    """Text with its line breaks and runs of spaces as single spaces (Markdown wraps)."""
    return " ".join(text.split())


def test_a_dfm_run_relies_on_the_paper_and_its_contact_laws():
    assert _keys(orthogonal_case()) == [PAPER.key, FLORES.key, FRICTION.key]


def test_prb_adds_howell_and_its_buckling_link_timoshenko_and_gere():
    case = orthogonal_case()
    prb = case.replace(model=case.model.replace(kind="prb"))
    rigid = case.replace(model=case.model.replace(kind="prb", prb_link="rigid"))
    assert _keys(prb) == [PAPER.key, FLORES.key, FRICTION.key, HOWELL.key,
                          TIMOSHENKO_GERE.key]
    assert _keys(rigid) == [PAPER.key, FLORES.key, FRICTION.key, HOWELL.key]


def test_the_stick_slip_law_adds_its_reset_integrators_source():
    case = orthogonal_case()
    stick_slip = case.replace(contact=case.contact.replace(friction_model="stick-slip"))
    assert _keys(stick_slip) == [PAPER.key, FLORES.key, FRICTION.key, HAESSIG_FRIEDLAND.key]


def test_contact_between_bristles_adds_its_law():
    case = orthogonal_case()
    touching = case.replace(contact=case.contact.replace(between_bristles=True))
    assert _keys(touching)[-1] == BRISTLE_CONTACT.key


def test_a_record_has_a_doi_only_where_the_reference_has_one():
    assert PAPER.record()["doi"] == "10.1007/s11044-024-09985-1"
    assert "doi" not in HOWELL.record()
    assert set(Reference("k", "c", "u").record()) == {"key", "citation", "used_for"}


def test_docs_model_cites_every_reference_as_the_module_does():
    text = _flat((ROOT / "docs" / "model.md").read_text(encoding="utf-8"))
    for reference in (PAPER, FLORES, FRICTION, HOWELL, TIMOSHENKO_GERE, BRISTLE_CONTACT,
                      HAESSIG_FRIEDLAND):
        assert _flat(reference.citation) in text, reference.key
    assert f"https://doi.org/{PAPER.doi}" in text


def test_readme_cites_the_paper_as_the_module_does():
    text = _flat((ROOT / "README.md").read_text(encoding="utf-8"))
    assert f"{PAPER.citation}. https://doi.org/{PAPER.doi}" in text


def test_citation_cff_has_the_package_version_and_the_paper():
    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text(encoding="utf-8"))
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    assert cff["cff-version"] == "1.2.0"
    assert cff["version"] == project["version"]  # bump both together
    assert cff["license"] == project["license"]  # an SPDX expression in both
    assert cff["authors"] == [{"name": "exubrush developers"}]
    for entry, reference in zip(cff["references"], LITERATURE, strict=True):
        assert _flat(entry["title"]) in reference.citation
        assert f"({entry['year']})" in reference.citation
        assert entry.get("doi") == reference.doi
        assert all(author["family-names"] in reference.citation
                   for author in entry["authors"])
    assert cff["references"][0]["journal"] in PAPER.citation

def test_a_run_json_without_references_still_reads(tmp_path):
    record = {"status": "completed", "completed": True, "parameters": {}}
    (tmp_path / "run.json").write_text(json.dumps(record))
    assert run_record(tmp_path) == record
    assert recorded_status(tmp_path) == "completed"

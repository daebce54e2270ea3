"""Contact between the bristles of a group as one Exudyn ``ObjectGenericODE2``.

The object spans the handle's node and every node of the group's bristles. Its force user
function places each bristle's points (root and pivot on the handle, the nodes of its
model) from the coordinates Exudyn hands it, finds the touching capsules
(exubrush.contact.between) and returns their forces on the points' position coordinates;
its Jacobian user function returns the touching pairs' derivatives as sparse triplets, so
Exudyn's Jacobian never differentiates the whole group numerically and only coordinates in
contact are coupled. The object has no mass, stiffness or damping of its own.

Forces act on node positions only: a contact force between two points of two segments is
handed to the segments' end nodes, which keeps its resultant and moment; the couple of the
friction force about a filament's own axis (its radius times the friction force) is not
represented (docs/tufts.md).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import exudyn as exu
import exudyn.itemInterface as eii
import numpy as np

from exubrush.contact.between import (
    Chains,
    candidate_pairs,
    contact_forces,
    law_vector,
    pair_corners,
)
from exubrush.contact.between_kernel import (
    DIVERGED,
    POSITION_STEP,
    VELOCITY_STEP,
    group_forces,
    group_jacobian,
)
from exubrush.parameters.case import BristleContactLaw

# how much farther than a step needs [mm] the broad phase looks, so that its pairs serve
# the next steps too (BristleContact.refresh)
SKIN = 0.05


@dataclass
class BristleContact:
    """The contact object of a group and what the solve reads from it.

    Attributes
    ----------
    object_number : int
        The ObjectGenericODE2.
    counts, overlaps : list of float
        Touching capsule pairs and the deepest overlap [mm] at each state sampled by
        :meth:`sample` (converged states only).
    """

    chains: Chains
    law: BristleContactLaw
    coordinates: np.ndarray  # (points, 3): index of each point's coordinate in the object's q
    base: np.ndarray  # (points, 3): position of each point at q = 0 [mm]
    size: int  # coordinates of the object
    system_indices: np.ndarray  # (size,): the object's coordinates in the system's ODE2 vector
    object_number: int = -1
    counts: list = field(default_factory=list)
    overlaps: list = field(default_factory=list)
    # corner points (m, 4), radii (m, 2), joint flags (m, 4) and neighbours' far ends (m, 4)
    # of the segment pairs that may touch during the coming step (refresh); None: search at
    # every call
    candidate_corners: tuple | None = None
    law_numbers: np.ndarray = field(init=False)  # the law as the kernels take it
    # the point positions [mm] and the reach [mm] of the last search (refresh)
    searched_points: np.ndarray | None = None
    searched_reach: float = 0.0

    def __post_init__(self):
        self.law_numbers = law_vector(self.law)

    def points(self, q: np.ndarray) -> np.ndarray:
        """Point positions [mm] (or velocities [mm/s], with base 0) from the object's q."""
        return self.base + q[self.coordinates]

    def _pairs(self, points: np.ndarray, margin: float = 0.0) -> np.ndarray:
        """Segment pairs within ``margin`` [mm] of touching at ``points``; none for a
        diverged Newton iterate (rejected anyway)."""
        if not np.all(np.abs(points) < DIVERGED):
            return np.zeros((0, 2), int)
        return candidate_pairs(self.chains, points, margin=margin)

    def _candidate_corners(self, q) -> tuple:
        if self.candidate_corners is not None:
            return self.candidate_corners
        return pair_corners(self.chains, self._pairs(self.points(q)))

    def force(self, mbs, t, item, q, q_t):
        """Exudyn force user function: the contact forces on the object's coordinates."""
        out = np.zeros(self.size)
        q = np.asarray(q)
        corners, radii, inner, far = self._candidate_corners(q)
        if len(corners):
            group_forces(q, np.asarray(q_t), self.base, self.coordinates, corners, radii,
                         inner, far, self.law_numbers, out)
        return out

    def jacobian(self, mbs, t, item, q, q_t, f_position, f_velocity):
        """Exudyn Jacobian user function: −(∂f/∂q · f_position + ∂f/∂q_t · f_velocity) of
        the touching pairs, as sparse triplets in the object's coordinates."""
        matrix = exu.MatrixContainer()
        q = np.asarray(q)
        corners, radii, inner, far = self._candidate_corners(q)
        triplets = np.zeros((0, 3))
        if len(corners):
            triplets = group_jacobian(q, np.asarray(q_t), self.base, self.coordinates,
                                      corners, radii, inner, far, self.law_numbers, f_position,
                                      f_velocity, POSITION_STEP, VELOCITY_STEP)
        matrix.SetWithSparseMatrix(triplets, self.size, self.size)
        return matrix

    def _state(self, mbs):
        data = mbs.systemData
        return (np.asarray(data.GetODE2Coordinates())[self.system_indices],
                np.asarray(data.GetODE2Coordinates_t())[self.system_indices])

    def refresh(self, mbs, reach: float) -> None:
        """Before a step: the segment pairs that can touch within it, from the system's
        current (converged) state, their capsules grown by ``reach`` [mm]
        (:func:`contact_refresh`).

        The pairs are searched again when the last search no longer covers them (a Verlet
        list): a pair left out then was more than its reach apart, and no point has moved
        more than d since, so it is still more than that reach − 2d apart (a segments'
        distance changes by at most twice its ends' largest move). A new search grows the
        reach by :data:`SKIN` so that it lasts. They are also searched again when the last
        search reached more than two skins farther than this step needs: kept while it
        covers, a list keeps every pair that one fast or long step needed, and the force
        function pays for every candidate at every residual (docs/decisions/0025)."""
        q, _ = self._state(mbs)
        points = self.points(q)
        if not np.all(np.abs(points) < DIVERGED):  # search at every call instead
            self.candidate_corners = self.searched_points = None
            return
        if self.searched_points is not None:  # set and cleared with candidate_corners
            moved = np.sqrt(np.max(np.sum((points - self.searched_points) ** 2, axis=1)))
            if reach <= self.searched_reach - 2.0 * moved and (
                    self.searched_reach <= reach + 2.0 * SKIN):
                return
        self.searched_points, self.searched_reach = points, reach + SKIN
        self.candidate_corners = pair_corners(self.chains, self._pairs(points, reach + SKIN))

    def _contacts(self, mbs):
        """The touching pairs and their corner forces at the system's current state."""
        q, q_t = self._state(mbs)
        points = self.points(q)
        return contact_forces(self.chains, points, q_t[self.coordinates],
                              self._pairs(points), self.law)

    def sample(self, mbs) -> None:
        """Record the contacts of the system's current (converged) state."""
        contacts = self._contacts(mbs)
        self.counts.append(len(contacts.pairs))
        self.overlaps.append(float(contacts.overlap.max()) if len(contacts.pairs) else 0.0)

    def resultants(self, mbs) -> np.ndarray:
        """Total contact force [N] on each bristle of the group (bristles, 3) at the
        system's current state."""
        contacts = self._contacts(mbs)
        owner = np.zeros(len(self.base), int)
        owner[self.chains.starts] = self.chains.bristle
        owner[self.chains.ends] = self.chains.bristle
        totals = np.zeros((int(self.chains.bristle.max()) + 1, 3))
        np.add.at(totals, owner[contacts.corners].ravel(),
                  contacts.corner_forces.reshape(-1, 3))
        return totals


def contact_refresh(contact: BristleContact, margin: float = 0.1):
    """Step hook: the candidate pairs for the coming step attempt (BristleContact.refresh),
    with the capsules grown by ``margin`` [mm] plus twice the distance the fastest point
    covers in the attempt's step at its current speed relative to the group's common
    motion: pairs farther apart than that cannot touch within the attempt, so the force
    function need not search. Exudyn calls the hook before every attempt, with t at the
    attempt's end, so the attempt's step is known (a longer one later gets its own refresh);
    the common motion is the midrange of the points' velocities per axis, a translation
    of all of them (the handle's slide) that brings no pair closer.

    Sized by the largest step the solver might take (10 ms mid-stroke) and absolute speeds
    (the slide's), the list held nearly every segment pair of a 19-filament tuft through
    the stroke, whose steps are mostly microseconds (docs/decisions/0025)."""
    start = exu.ConfigurationType.StartOfStep

    def refresh(mbs, t):
        data = mbs.systemData
        q_t = np.asarray(data.GetODE2Coordinates_t())[contact.system_indices]
        velocities = q_t[contact.coordinates]
        common = 0.5 * (velocities.max(axis=0) + velocities.min(axis=0))
        speed = np.linalg.norm(velocities - common, axis=1).max()
        contact.refresh(mbs, margin + 2.0 * speed * max(t - data.GetTime(start), 0.0))

    return refresh


def _position_block(mbs, node) -> tuple[int, np.ndarray]:
    """(number of coordinates, reference position [mm]) of a node whose first three
    coordinates are its position's displacement."""
    reference = exu.ConfigurationType.Reference
    count = len(mbs.GetNodeOutput(node, exu.OutputVariableType.Coordinates,
                                  configuration=reference))
    position = np.asarray(mbs.GetNodeOutput(node, exu.OutputVariableType.Position,
                                            configuration=reference))
    return count, position


def add_bristle_contact(mbs, handle_node, polylines: list[list], radii: list[float],
                        law: BristleContactLaw) -> BristleContact:
    """Add the contact between the bristles of one system (call before ``Assemble``).

    Parameters
    ----------
    handle_node : int
        The handle's node; its first three coordinates move the points fixed to it (the
        handle does not rotate).
    polylines : list of list
        Per bristle, its points from the root: ``("handle", offset)`` for a point fixed to
        the handle (offset [mm] from the handle node's reference position) or ``("node",
        n)`` for a node's position.
    radii : list of float
        Each bristle's contact radius [mm].
    """
    nodes = [handle_node]
    for line in polylines:
        nodes += [n for kind, n in line if kind == "node"]
    offsets, references, total = {}, {}, 0
    for node in nodes:
        count, reference = _position_block(mbs, node)
        offsets[node], references[node] = total, reference
        total += count
    coordinates, base, indices = [], [], []
    handle = np.arange(3) + offsets[handle_node]
    for line in polylines:
        chain = []
        for kind, value in line:
            chain.append(len(base))
            if kind == "handle":
                coordinates.append(handle)
                base.append(references[handle_node] + np.asarray(value, float))
            else:
                coordinates.append(np.arange(3) + offsets[value])
                base.append(references[value])
        indices.append(chain)
    contact = BristleContact(
        chains=Chains.from_polylines(indices, radii), law=law,
        coordinates=np.array(coordinates, int), base=np.array(base, float), size=total,
        system_indices=np.zeros(total, int))
    empty = exu.MatrixContainer()
    empty.SetWithSparseMatrix(np.zeros((0, 3)), total, total)
    contact.object_number = mbs.AddObject(eii.ObjectGenericODE2(
        nodeNumbers=nodes, massMatrix=empty, forceVector=[0.0] * total,
        forceUserFunction=contact.force, jacobianUserFunction=contact.jacobian,
        visualization=eii.VObjectGenericODE2(show=False)))
    contact.nodes = nodes
    return contact


def locate_in_system(mbs, contact: BristleContact) -> None:
    """Store where the object's coordinates sit in the system's ODE2 vector (after
    ``Assemble``), for :meth:`BristleContact.sample`."""
    indices = []
    for node in contact.nodes:
        start = mbs.GetNodeODE2Index(node)
        indices += range(start, start + _position_block(mbs, node)[0])
    contact.system_indices = np.array(indices, int)

"""Structure analysis of planar mechanisms: mobility, redundant constraints, Assur groups.

Source: the lever-mechanism textbook, §2.2-2.3 (mobility by Chebyshev, redundant constraints and
local mobility, structural groups after Assur and Artobolevsky) and its worked six-link example;
the rules used here and where the printed textbook differs are in docs/mechanisms.md §3.

A mechanism is plain data:

* ``links``: link names (strings), one of which is the ``frame``;
* ``joints``: each a :class:`Joint`, a tuple ``(name, kind, links)`` or a mapping with the keys
  ``name``, ``kind``, ``links``.  ``kind`` is ``"revolute"`` or ``"prismatic"`` (lower pairs,
  1 freedom each) or ``"higher"`` (cam or gear contact, 2 freedoms).  A joint that joins k > 2
  links (a multiple hinge) counts as k - 1 pairs.

Counting rule for a subset G of moving links attached to the rest of the mechanism (the rest held
still): a joint with m links in G contributes m pairs if it also holds a link outside G (the
frame included), else m - 1.  The mobility of G is 3 |G| - 2 p1 - p2 with these counts (Eq. 3.4),
and the mobility of the whole mechanism is the sum of those of G and of the rest, so removing a
group of mobility 0 leaves the rest with the mobility of the whole.

Everything here is pure Python on small inputs; invalid input raises ``ValueError`` with one
sentence naming the problem.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from itertools import combinations

LOWER_KINDS = ("revolute", "prismatic")
HIGHER_KIND = "higher"
KINDS = (*LOWER_KINDS, HIGHER_KIND)
_LETTER = {"revolute": "R", "prismatic": "P", "higher": "H"}


@dataclass(frozen=True)
class Joint:
    """A kinematic pair (or multiple hinge) joining two or more links.

    Attributes
    ----------
    name : the joint's name.
    kind : "revolute", "prismatic" (lower pairs, 1 freedom) or "higher" (2 freedoms).
    links : names of the links it joins (k >= 2; k - 1 pairs).
    """

    name: str
    kind: str
    links: tuple[str, ...]

    @property
    def pairs(self) -> int:
        """Number of pairs the joint counts for: k - 1."""
        return len(self.links) - 1

    @property
    def lower(self) -> bool:
        return self.kind in LOWER_KINDS


@dataclass(frozen=True)
class AssurGroup:
    """One Assur structural group (mobility 0 when its leads are held).

    Attributes
    ----------
    links : the group's links, in input order.
    joints : every joint touching the group (internal joints and leads), in input order.
    internal_joints : joints whose links all belong to the group.
    lead_joints : joints that attach the group to the frame, a driver or an earlier group.
    group_class : class after Artobolevsky: the number of pairs in the most complex closed
        contour of internal pairs, or of the basic link (the link with most joints), at least 2.
    order : number of leads (external pairs) by which the group is attached.
    dyad_type : for a two-link group, the pair letters lead-internal-lead, e.g. "RRR", "RRP",
        "RPR", "PRP"; None for larger groups.
    """

    links: tuple[str, ...]
    joints: tuple[str, ...]
    internal_joints: tuple[str, ...]
    lead_joints: tuple[str, ...]
    group_class: int
    order: int
    dyad_type: str | None


@dataclass(frozen=True)
class StructureAnalysis:
    """Structure of a planar mechanism (docs/mechanisms.md §3).

    Attributes
    ----------
    moving_links : n, links other than the frame (passive links included).
    lower_pairs, higher_pairs : p1, p2 (a k-link joint counts k - 1 pairs).
    formula_mobility : Chebyshev's W = 3n - 2 p1 - p2 (Eq. 3.1).
    redundant_constraints : q, from the passive links marked in the input (Eq. 3.3).
    local_mobilities : local freedoms marked in the input.
    mobility : the mechanism's working mobility W = 3n - 2 p1 - p2 + q - local (Eq. 3.2).
    drivers : the driving links (given, or the first frame-pivoted links that decompose).
    groups : Assur groups in the order they are attached (first attached first).
    mechanism_class : the highest group class (1 when there is no group).
    decomposed : True when the mechanism is exactly the drivers plus the groups.
    reason : why the decomposition failed ("" when decomposed).
    """

    moving_links: int
    lower_pairs: int
    higher_pairs: int
    formula_mobility: int
    redundant_constraints: int
    local_mobilities: int
    mobility: int
    drivers: tuple[str, ...]
    groups: tuple[AssurGroup, ...]
    mechanism_class: int
    decomposed: bool
    reason: str


# --------------------------------------------------------------------------- input
def _joint(item) -> Joint:
    if isinstance(item, Joint):
        name, kind, links = item.name, item.kind, item.links
    elif isinstance(item, Mapping):
        missing = {"name", "kind", "links"} - set(item)
        if missing:
            raise ValueError(f"a joint mapping lacks the key(s) {', '.join(sorted(missing))}.")
        name, kind, links = item["name"], item["kind"], item["links"]
    elif isinstance(item, Sequence) and not isinstance(item, str) and len(item) == 3:
        name, kind, links = item
    else:
        raise ValueError(f"a joint must be a Joint, a (name, kind, links) tuple or a mapping, not {item!r}.")
    if isinstance(links, str) or not isinstance(links, Iterable):
        raise ValueError(f"joint {name!r} must list its links as a sequence of names.")
    return Joint(str(name), str(kind), tuple(str(x) for x in links))


def _mechanism(links, frame, joints):
    """Validate and normalise: (tuple of link names, frame, tuple of Joint)."""
    if isinstance(links, str) or not isinstance(links, Iterable):
        raise ValueError("links must be a sequence of link names.")
    names = tuple(str(x) for x in links)
    if len(set(names)) != len(names):
        dup = sorted({x for x in names if names.count(x) > 1})
        raise ValueError(f"link name(s) {', '.join(dup)} appear more than once.")
    frame = str(frame)
    if frame not in names:
        raise ValueError(f"the frame {frame!r} is not one of the links.")
    if len(names) < 2:
        raise ValueError("a mechanism needs the frame and at least one moving link.")
    out = tuple(_joint(j) for j in joints)
    seen = set()
    for j in out:
        if j.name in seen:
            raise ValueError(f"joint name {j.name!r} appears more than once.")
        seen.add(j.name)
        if j.kind not in KINDS:
            raise ValueError(f"joint {j.name!r} has kind {j.kind!r}; use revolute, prismatic or higher.")
        if len(j.links) < 2:
            raise ValueError(f"joint {j.name!r} must join at least two links.")
        if len(set(j.links)) != len(j.links):
            raise ValueError(f"joint {j.name!r} lists a link twice.")
        unknown = [x for x in j.links if x not in names]
        if unknown:
            raise ValueError(f"joint {j.name!r} names the unknown link {unknown[0]!r}.")
        if j.kind == HIGHER_KIND and len(j.links) != 2:
            raise ValueError(f"higher pair {j.name!r} must join exactly two links.")
    # every link reachable from the frame
    reached = _reachable(frame, out)
    lost = [x for x in names if x not in reached]
    if lost:
        raise ValueError(f"link {lost[0]!r} is not connected to the frame through any joint.")
    return names, frame, out


def _count(joints, group):
    """(lower pairs, higher pairs) of the joints touching ``group`` with the rest held (Eq. 3.4)."""
    p1 = p2 = 0
    for j in joints:
        m = sum(1 for x in j.links if x in group)
        if m == 0:
            continue
        pairs = m if any(x not in group for x in j.links) else m - 1
        if j.lower:
            p1 += pairs
        else:
            p2 += pairs
    return p1, p2


def _restrict(joints, present):
    """Joints with their links cut to ``present``; joints left with fewer than 2 links vanish."""
    out = []
    for j in joints:
        kept = tuple(x for x in j.links if x in present)
        if len(kept) >= 2:
            out.append(Joint(j.name, j.kind, kept))
    return tuple(out)


# --------------------------------------------------------------------------- counting
def pair_counts(links, frame, joints):
    """(n, p1, p2): moving links, lower pairs and higher pairs (a k-link joint counts k - 1).

    Source: the lever-mechanism textbook, §2.2 (Chebyshev's formula); docs/mechanisms.md §3.
    """
    names, frame, js = _mechanism(links, frame, joints)
    p1 = sum(j.pairs for j in js if j.lower)
    p2 = sum(j.pairs for j in js if not j.lower)
    return len(names) - 1, p1, p2


def mobility(links, frame, joints) -> int:
    """Chebyshev's mobility W = 3n - 2 p1 - p2 of a planar mechanism (Eq. 3.1).

    Parameters
    ----------
    links : link names; frame : the fixed link's name; joints : see the module docstring.

    Returns
    -------
    W (int).  It counts constraints only: a mechanism with redundant (passive) constraints can
    move although W <= 0; see :func:`analyse_structure` with ``passive_links``.
    Source: the lever-mechanism textbook, §2.2; docs/mechanisms.md §3.
    """
    n, p1, p2 = pair_counts(links, frame, joints)
    return 3 * n - 2 * p1 - p2  # Eq. (3.1)


def redundant_constraints(formula_mobility: int, mobility: int, local_mobilities: int = 0) -> int:
    """Redundant constraints q = W + W_local - W_formula (Eq. 3.3).

    Parameters
    ----------
    formula_mobility : Chebyshev's 3n - 2 p1 - p2.
    mobility : the working mobility W0 (number of drivers the mechanism needs).
    local_mobilities : local freedoms W_local (e.g. a follower roller's spin).

    Returns
    -------
    q >= 0.  The printed textbook has q = W0 + Wm + W with a plus sign before the formula
    mobility; a four-bar (W0 = 1, Wm = 0, W = 1, q = 0) shows the sign must be minus.
    Source: the lever-mechanism textbook, §2.2; docs/mechanisms.md §3.
    """
    for label, value in (
        ("formula_mobility", formula_mobility),
        ("mobility", mobility),
        ("local_mobilities", local_mobilities),
    ):
        if not isinstance(value, int) or isinstance(value, bool):
            raise ValueError(f"{label} must be an integer, not {value!r}.")
    if local_mobilities < 0:
        raise ValueError("local_mobilities must not be negative.")
    q = mobility + local_mobilities - formula_mobility  # Eq. (3.3)
    if q < 0:
        raise ValueError(
            f"the mechanism would have q = {q} < 0 redundant constraints: a working mobility of "
            f"{mobility} with {local_mobilities} local freedom(s) exceeds what the pairs allow."
        )
    return q


# --------------------------------------------------------------------------- Assur groups
def _reachable(start, joints, within=None) -> set:
    """The links joined to ``start`` through ``joints``, directly or through other links (only
    links of ``within``, when given), and ``start`` itself."""
    seen, todo = {start}, [start]
    while todo:
        here = todo.pop()
        for j in joints:
            if here in j.links:
                for x in j.links:
                    if (within is None or x in within) and x not in seen:
                        seen.add(x)
                        todo.append(x)
    return seen


def _connected(group, joints):
    group = set(group)
    return _reachable(next(iter(group)), joints, group) == group


def _distances(drivers, present, joints, frame):
    """Graph distance of each present moving link from the drivers, not passing the frame."""
    dist = {d: 0 for d in drivers}
    todo = list(drivers)
    while todo:
        nxt = []
        for here in todo:
            for j in joints:
                if here in j.links:
                    for x in j.links:
                        if x != frame and x in present and x not in dist:
                            dist[x] = dist[here] + 1
                            nxt.append(x)
        todo = nxt
    return dist


def _no_loose_part(group, joints, present):
    """True if no part S of the group is over-constrained on its own (mobility < 0 with the rest
    of the group taken away), which would leave another part loose although the count is 0."""
    members = sorted(group)
    for size in range(1, len(members)):
        for part in combinations(members, size):
            part = set(part)
            p1, p2 = _count(_restrict(joints, present - (group - part)), part)
            if 3 * len(part) - 2 * p1 - p2 < 0:  # Eq. (3.4)
                return False
    return True


def _longest_contour(group, internal):
    """Pairs in the longest closed contour of internal pairs (cycle in the link-joint graph)."""
    best = 0
    edges = [(j.name, [x for x in j.links if x in group]) for j in internal]
    links = sorted(group)

    def walk(start, here, used_links, used_joints, length):
        nonlocal best
        for name, members in edges:
            if name in used_joints or here not in members:
                continue
            for x in members:
                if x == here:
                    continue
                if x == start and length >= 1:
                    best = max(best, length + 1)
                elif x not in used_links and x > start:
                    walk(start, x, used_links | {x}, used_joints | {name}, length + 1)

    for s in links:
        walk(s, s, {s}, frozenset(), 0)
    return best


def _describe(group, joints, links_order):
    """AssurGroup for ``group`` (a set) among the present ``joints``."""
    touching = [j for j in joints if any(x in group for x in j.links)]
    internal = [j for j in touching if all(x in group for x in j.links)]
    leads = [j for j in touching if any(x not in group for x in j.links)]
    # joints in which two or more group links meet also join the group internally
    inner = [j for j in touching if sum(1 for x in j.links if x in group) >= 2]
    vertices = max(sum(1 for j in touching if x in j.links) for x in group)
    group_class = max(2, vertices, _longest_contour(group, inner))
    ordered = tuple(x for x in links_order if x in group)
    dyad = None
    if len(group) == 2 and len(internal) == 1 and len(leads) == 2:
        a, b = ordered
        lead_a = next((j for j in leads if a in j.links), None)
        lead_b = next((j for j in leads if b in j.links and j is not lead_a), None)
        if lead_a is not None and lead_b is not None:
            dyad = _LETTER[lead_a.kind] + _LETTER[internal[0].kind] + _LETTER[lead_b.kind]
    return AssurGroup(
        links=ordered,
        joints=tuple(j.name for j in touching),
        internal_joints=tuple(j.name for j in internal),
        lead_joints=tuple(j.name for j in leads),
        group_class=group_class,
        order=len(leads),
        dyad_type=dyad,
    )


def _decompose(names, frame, joints, drivers):
    """(groups in attachment order, reason); reason is '' on success."""
    moving = [x for x in names if x != frame]
    if any(not j.lower for j in joints):
        return (), "higher pairs must be replaced by lower-pair chains before the Assur decomposition"
    present = set(moving)
    removed = []
    while present - set(drivers):
        candidates = [x for x in moving if x in present and x not in drivers]
        js = _restrict(joints, present | {frame})
        dist = _distances(drivers, present, js, frame)
        found = None
        for size in range(2, len(candidates) + 1, 2):
            valid = []
            for combo in combinations(candidates, size):
                group = set(combo)
                p1, p2 = _count(js, group)
                if 3 * size - 2 * p1 - p2 != 0 or not _connected(group, js):  # Eq. (3.4)
                    continue
                if not _no_loose_part(group, js, present | {frame}):
                    continue
                far = min(dist.get(x, len(names)) for x in group)
                valid.append((far, sorted((moving.index(x) for x in combo), reverse=True), group))
            if valid:
                # the farthest from the drivers; among equals the last in input order, so that the
                # groups are attached in the order the links are numbered
                found = max(valid, key=lambda v: (v[0], v[1]))[2]
                break
        if found is None:
            rest = ", ".join(x for x in moving if x in present and x not in drivers)
            return tuple(reversed(removed)), (
                f"links {rest} form no Assur group of mobility 0 with drivers {', '.join(drivers)}"
            )
        removed.append(_describe(found, js, moving))
        present -= found
    # what is left must be the primary mechanisms: each driver pivoted on (or sliding in) the frame
    js = _restrict(joints, set(drivers) | {frame})
    for d in drivers:
        mine = [j for j in js if d in j.links]
        if len(mine) != 1 or set(mine[0].links) != {d, frame}:
            return tuple(reversed(removed)), (
                f"driver {d} is not joined to the frame alone by one lower pair once the groups are removed"
            )
    return tuple(reversed(removed)), ""


def _check_links(chosen, names, frame, role):
    if isinstance(chosen, str):
        chosen = (chosen,)
    chosen = tuple(str(d) for d in chosen)
    for d in chosen:
        if d not in names:
            raise ValueError(f"{role} {d!r} is not one of the links.")
        if d == frame:
            raise ValueError(f"the frame cannot be a {role}.")
    if len(set(chosen)) != len(chosen):
        raise ValueError(f"a {role} is listed twice.")
    return chosen


def _check_drivers(drivers, names, frame):
    return _check_links(drivers, names, frame, "driver")


def assur_groups(links, frame, joints, drivers):
    """Assur groups of a mechanism with the given driving links, in the order they are attached.

    The groups are removed one at a time, farthest from the drivers first; each is the smallest
    set of non-driving links (2, then 4, ... links) whose mobility with the rest held is 0
    (Eq. 3.4) and whose removal therefore leaves the rest with the same mobility.  What remains
    must be the drivers, each joined to the frame by one lower pair.

    Parameters
    ----------
    links, frame, joints : the mechanism (module docstring).
    drivers : name or names of the driving links.

    Returns
    -------
    tuple of AssurGroup, first attached first.

    Raises
    ------
    ValueError : invalid input, or no decomposition with these drivers (the message says why).
    Source: the lever-mechanism textbook, §2.3 and its six-link example; docs/mechanisms.md §3.
    """
    names, frame, js = _mechanism(links, frame, joints)
    drivers = _check_drivers(drivers, names, frame)
    groups, reason = _decompose(names, frame, js, drivers)
    if reason:
        raise ValueError(f"no Assur decomposition: {reason}.")
    return groups


def _pivoted(names, frame, joints):
    """Moving links joined to the frame by a lower pair, in input order."""
    return [
        x for x in names if x != frame and any(j.lower and frame in j.links and x in j.links for j in joints)
    ]


def driving_links(links, frame, joints, passive_links=(), local_mobilities=0):
    """The driving links: the first W frame-pivoted links (input order) that decompose into Assur groups.

    Returns
    -------
    tuple of link names (empty when no choice decomposes or W <= 0).  The textbook numbers
    links from the driver, so list the intended driver first.  Source: docs/mechanisms.md §3.
    """
    return analyse_structure(links, frame, joints, None, passive_links, local_mobilities).drivers


def analyse_structure(links, frame, joints, drivers=None, passive_links=(), local_mobilities=0):
    """Mobility, redundant constraints, drivers and Assur groups of a planar mechanism.

    Parameters
    ----------
    links, frame, joints : the mechanism (module docstring).
    drivers : driving link name(s), or None to pick the first frame-pivoted links (input order)
        for which the decomposition succeeds.
    passive_links : links whose constraints are redundant (removing them leaves the motion
        unchanged, e.g. the third crank of a double parallelogram).  q is counted from them
        (Eq. 3.3) and the decomposition runs on the mechanism without them.
    local_mobilities : number of local freedoms (e.g. a follower roller's spin), >= 0.

    Returns
    -------
    StructureAnalysis.  W = 3n - 2 p1 - p2 + q - local (Eq. 3.2).
    Source: the lever-mechanism textbook, §2.2-2.3; docs/mechanisms.md §3.
    """
    names, frame, js = _mechanism(links, frame, joints)
    if not isinstance(local_mobilities, int) or isinstance(local_mobilities, bool) or local_mobilities < 0:
        raise ValueError(f"local_mobilities must be a non-negative integer, not {local_mobilities!r}.")
    passive = _check_links(passive_links, names, frame, "passive link") if passive_links else ()
    n, p1, p2 = pair_counts(names, frame, js)
    formula = 3 * n - 2 * p1 - p2  # Eq. (3.1)
    active = tuple(x for x in names if x not in passive)
    active_joints = _restrict(js, set(active))
    try:
        _mechanism(active, frame, active_joints)
    except ValueError as err:
        raise ValueError(f"without the passive links the mechanism falls apart: {err}") from None
    reduced = (
        3 * (len(active) - 1)
        - 2 * sum(j.pairs for j in active_joints if j.lower)
        - sum(j.pairs for j in active_joints if not j.lower)
    )
    q = reduced - formula  # Eq. (3.3) with W0 + Wm = the reduced mechanism's count
    if q < 0:
        raise ValueError(
            f"the passive links {', '.join(passive)} add freedoms instead of redundant constraints."
        )
    working = formula + q - local_mobilities  # Eq. (3.2)
    if drivers is not None:
        chosen = _check_drivers(drivers, names, frame)
        if set(chosen) & set(passive):
            raise ValueError("a driver cannot be a passive link.")
        if len(chosen) != working:
            groups, reason = (), (f"{len(chosen)} driver(s) given but the working mobility is {working}")
        else:
            groups, reason = _decompose(active, frame, active_joints, chosen)
    elif working <= 0:
        chosen, groups, reason = (), (), f"the working mobility is {working}: a structure, nothing to drive"
    elif any(not j.lower for j in active_joints):
        chosen, groups, reason = (), *_decompose(active, frame, active_joints, ())
    else:
        chosen, groups, reason = (), (), f"no {working} frame-pivoted link(s) decompose into Assur groups"
        first = ""
        for combo in combinations(_pivoted(active, frame, active_joints), working):
            g, r = _decompose(active, frame, active_joints, combo)
            if not r:
                chosen, groups, reason = combo, g, ""
                break
            first = first or r
        if reason and first:
            reason = f"{reason} (the first choice fails: {first})"
    return StructureAnalysis(
        moving_links=n,
        lower_pairs=p1,
        higher_pairs=p2,
        formula_mobility=formula,
        redundant_constraints=q,
        local_mobilities=local_mobilities,
        mobility=working,
        drivers=tuple(chosen),
        groups=tuple(groups),
        mechanism_class=max((g.group_class for g in groups), default=1),
        decomposed=not reason,
        reason=reason,
    )

"""Structure analysis (docs/mechanisms.md §3): mobility, redundant constraints, Assur groups.

Independent routes, none of which calls the code under test:

* an instantaneous-kinematics check written in this file: every joint gets a random point in the
  plane (a prismatic pair a random axis, a higher pair a random contact normal), every moving
  link the unknowns (vx, vy, omega), every pair its velocity constraints; the rank of that
  Jacobian gives the mobility for generic geometry (3n - rank), and a group is an Assur group
  iff it is rigid (full rank) with the rest held;
* mechanisms built here by attaching known dyads one after another (hypothesis), so the groups
  the decomposition must find are known from the construction;
* the textbook's worked six-link example (links 1-5, seven lower pairs, W = 1, groups (4, 5) then
  (2, 3)) and its double-parallelogram example with the passive rod (Fig. 1.12).
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pumplink.mechanisms import structure as S


def R(name, *links):
    return (name, "revolute", links)


def P(name, *links):
    return (name, "prismatic", links)


FOUR_BAR = dict(
    links=["0", "1", "2", "3"],
    frame="0",
    joints=[R("A", "0", "1"), R("B", "1", "2"), R("C", "2", "3"), R("D", "3", "0")],
)
SLIDER_CRANK = dict(
    links=["0", "1", "2", "3"],
    frame="0",
    joints=[R("A", "0", "1"), R("B", "1", "2"), R("C", "2", "3"), P("D", "3", "0")],
)
FIVE_BAR = dict(
    links=["0", "1", "2", "3", "4"],
    frame="0",
    joints=[R("A", "0", "1"), R("B", "1", "2"), R("C", "2", "3"), R("D", "3", "4"), R("E", "4", "0")],
)
# Watt chain: the two ternary links (frame 0 and rocker 3) are joined directly (joint D)
WATT = dict(
    links=["0", "1", "2", "3", "4", "5"],
    frame="0",
    joints=[
        R("A", "0", "1"),
        R("B", "1", "2"),
        R("C", "2", "3"),
        R("D", "0", "3"),
        R("E", "3", "4"),
        R("G", "4", "5"),
        R("F", "5", "0"),
    ],
)
# Stephenson chain: the ternary links (frame 0 and coupler 2) are not joined to each other
STEPHENSON = dict(
    links=["0", "1", "2", "3", "4", "5"],
    frame="0",
    joints=[
        R("A", "0", "1"),
        R("B", "1", "2"),
        R("C", "2", "3"),
        R("D", "3", "0"),
        R("E", "2", "4"),
        R("G", "4", "5"),
        R("F", "5", "0"),
    ],
)
# the textbook's six-link example: crank 1, rods 2 and 4, rocker 3, slider 5; hinge C joins 2, 3, 4
TEXTBOOK_SIX = dict(
    links=["0", "1", "2", "3", "4", "5"],
    frame="0",
    joints=[
        R("A", "0", "1"),
        R("B", "1", "2"),
        R("C", "2", "3", "4"),
        R("D", "0", "3"),
        R("E", "4", "5"),
        P("F", "5", "0"),
    ],
)
# double parallelogram (textbook Fig. 1.12): cranks 1 (OA, carrying D) and 4 (CB, carrying E),
# coupler 3 (AB) and the passive rod 2 (DE)
DOUBLE_PARALLELOGRAM = dict(
    links=["0", "1", "2", "3", "4"],
    frame="0",
    joints=[
        R("O", "0", "1"),
        R("C", "0", "4"),
        R("A", "1", "3"),
        R("B", "3", "4"),
        R("D", "1", "2"),
        R("E", "2", "4"),
    ],
)


# --------------------------------------------------------------------------- instantaneous kinematics
def jacobian(mech, points, axes, unknown=None):
    """Velocity-constraint matrix of the mechanism at a configuration (columns: vx, vy, w per link).

    ``points`` maps joint name -> (x, y); ``axes`` maps prismatic/higher joint -> unit vector (the
    slide axis / contact normal).  ``unknown`` lists the links that may move (default: all moving
    links); the others are held still like the frame.
    """
    moving = [x for x in mech["links"] if x != mech["frame"]] if unknown is None else list(unknown)
    col = {x: 3 * i for i, x in enumerate(moving)}
    rows = []

    def velocity_row(link, p, sign):
        """Coefficients of sign * (velocity of the link's point p), x and y rows."""
        rx, ry = np.zeros(3 * len(moving)), np.zeros(3 * len(moving))
        if link in col:
            c = col[link]
            rx[c], rx[c + 2] = sign, -sign * p[1]
            ry[c + 1], ry[c + 2] = sign, sign * p[0]
        return rx, ry

    for name, kind, links in mech["joints"]:
        p = points[name]
        for other in links[1:]:
            ax, ay = velocity_row(links[0], p, 1.0)
            bx, by = velocity_row(other, p, -1.0)
            dx, dy = ax + bx, ay + by
            if kind == "revolute":
                rows += [dx, dy]
            else:
                u = axes[name]
                n = np.array([-u[1], u[0]]) if kind == "prismatic" else u
                rows.append(n[0] * dx + n[1] * dy)
                if kind == "prismatic":
                    w = np.zeros(3 * len(moving))
                    for link, sign in ((links[0], 1.0), (other, -1.0)):
                        if link in col:
                            w[col[link] + 2] = sign
                    rows.append(w)
    return np.array(rows).reshape(-1, 3 * len(moving))


def random_geometry(mech, random_state):
    rng = np.random.default_rng(random_state)
    points = {j[0]: rng.normal(size=2) for j in mech["joints"]}
    axes = {}
    for j in mech["joints"]:
        a = rng.uniform(0, 2 * math.pi)
        axes[j[0]] = np.array([math.cos(a), math.sin(a)])
    return points, axes


def numeric_mobility(mech, random_state=1, points=None, axes=None):
    if points is None:
        points, axes = random_geometry(mech, random_state)
    J = jacobian(mech, points, axes)
    return J.shape[1] - np.linalg.matrix_rank(J, tol=1e-9)


def group_is_rigid(mech, group_links, present, random_state=1):
    """The group cannot move with every other present link held (and links not present removed)."""
    sub = dict(mech)
    sub["joints"] = [
        (n, k, tuple(x for x in ls if x in present or x == mech["frame"])) for n, k, ls in mech["joints"]
    ]
    sub["joints"] = [j for j in sub["joints"] if len(j[2]) >= 2]
    points, axes = random_geometry(mech, random_state)
    J = jacobian(sub, points, axes, unknown=group_links)
    return J.shape[1] == 0 or np.linalg.matrix_rank(J, tol=1e-9) == J.shape[1]


# --------------------------------------------------------------------------- named mechanisms
@pytest.mark.parametrize(
    "mech, w",
    [(FOUR_BAR, 1), (SLIDER_CRANK, 1), (FIVE_BAR, 2), (WATT, 1), (STEPHENSON, 1), (TEXTBOOK_SIX, 1)],
)
def test_mobility_matches_instantaneous_kinematics(mech, w):
    assert S.mobility(**mech) == w
    assert numeric_mobility(mech) == w


def test_four_bar_and_slider_crank():
    for mech, kind in ((FOUR_BAR, "RRR"), (SLIDER_CRANK, "RRP")):
        a = S.analyse_structure(**mech)
        assert a.decomposed and a.drivers == ("1",) and a.mobility == 1
        (g,) = a.groups
        assert g.links == ("2", "3") and g.group_class == 2 and g.order == 2 and g.dyad_type == kind
        assert set(g.lead_joints) == {"B", "D"} and g.internal_joints == ("C",)
        assert a.mechanism_class == 2


def test_five_bar_has_two_drivers():
    a = S.analyse_structure(**FIVE_BAR)
    assert a.formula_mobility == 2 and a.mobility == 2
    assert a.drivers == ("1", "4")
    (g,) = a.groups
    assert g.links == ("2", "3") and g.order == 2
    assert not S.analyse_structure(**FIVE_BAR, drivers=["1"]).decomposed  # one driver is too few


def test_watt_chain_two_class_two_groups():
    a = S.analyse_structure(**WATT)
    assert a.drivers == ("1",)
    assert [g.links for g in a.groups] == [("2", "3"), ("4", "5")]  # attached in this order
    assert all(g.group_class == 2 and g.order == 2 for g in a.groups)


@pytest.mark.parametrize(
    "driver, expected",
    [
        ("1", [(("2", "3"), 2, 2), (("4", "5"), 2, 2)]),
        ("5", [(("1", "2", "3", "4"), 3, 3)]),
    ],
)
def test_stephenson_chain_depends_on_the_driver(driver, expected):
    a = S.analyse_structure(**STEPHENSON, drivers=driver)
    assert a.decomposed
    assert [(g.links, g.group_class, g.order) for g in a.groups] == expected
    assert a.mechanism_class == max(c for _, c, _ in expected)
    present = set(STEPHENSON["links"]) - {"0"}
    for g in reversed(a.groups):
        assert group_is_rigid(STEPHENSON, g.links, present)
        present -= set(g.links)


def test_ternary_link_third_joint_is_not_a_group():
    """Every group is a set of links with mobility 0; the ternary links' third joints (D of the
    Watt chain, E of the Stephenson chain) are leads or internal pairs, never a group of their own."""
    for mech in (WATT, STEPHENSON):
        a = S.analyse_structure(**mech)
        assert len(a.groups) == 2 and all(len(g.links) == 2 for g in a.groups)
        pairs = sum(len(g.lead_joints) + len(g.internal_joints) for g in a.groups) + len(a.drivers)
        assert pairs == 7  # each of the 7 pairs in exactly one group or a primary mechanism


def test_textbook_six_link_example():
    """The textbook's worked example: n = 5, p1 = 7 (6 revolute + 1 prismatic), p2 = 0, W = 1; the
    group (4, 5) farthest from the crank comes off first (RRP with leads C and the slider guide),
    then (2, 3) (RRR with leads B and D); both 2nd class, 2nd order."""
    a = S.analyse_structure(**TEXTBOOK_SIX)
    assert (a.moving_links, a.lower_pairs, a.higher_pairs, a.formula_mobility) == (5, 7, 0, 1)
    assert a.drivers == ("1",)
    first, second = a.groups
    assert first.links == ("2", "3") and second.links == ("4", "5")  # attachment order
    assert second.dyad_type == "RRP" and set(second.lead_joints) == {"C", "F"}
    assert first.dyad_type == "RRR" and set(first.lead_joints) == {"B", "D"}
    assert first.internal_joints == ("C",)  # the multiple hinge: C23 inside, C24 a lead of (4, 5)
    assert all(g.group_class == 2 and g.order == 2 for g in a.groups)
    present = {"1", "2", "3", "4", "5"}
    assert group_is_rigid(TEXTBOOK_SIX, ("4", "5"), present)
    assert group_is_rigid(TEXTBOOK_SIX, ("2", "3"), {"1", "2", "3"})
    assert S.pair_counts(**TEXTBOOK_SIX) == (5, 7, 0)


def _parallelogram_geometry(t=0.4):
    origin, c, a = np.array([0.0, 0.0]), np.array([2.0, 0.0]), np.array([0.3, 1.0])
    b = a + (c - origin)
    return {"O": origin, "C": c, "A": a, "B": b, "D": t * a, "E": c + t * (b - c)}


def test_double_parallelogram_redundant_constraint():
    mech = DOUBLE_PARALLELOGRAM
    assert S.mobility(**mech) == 0  # Chebyshev: a structure ...
    assert numeric_mobility(mech) == 0  # ... and so it is with generic lengths
    # ... but with the textbook's parallel, equal rods it moves: one freedom
    assert numeric_mobility(mech, points=_parallelogram_geometry(), axes={}) == 1
    for phi in np.linspace(0, 2 * math.pi, 13):  # finite motion: the rod DE keeps its length
        A = math.hypot(0.3, 1.0) * np.array([math.cos(phi), math.sin(phi)])
        D, E = 0.4 * A, np.array([2.0, 0.0]) + 0.4 * A
        assert np.linalg.norm(E - D) == pytest.approx(2.0, rel=1e-15)
    a = S.analyse_structure(**mech, passive_links=["2"])
    assert a.formula_mobility == 0 and a.redundant_constraints == 1 and a.mobility == 1
    assert a.decomposed and a.drivers == ("1",)
    assert [g.links for g in a.groups] == [("3", "4")]
    b = S.analyse_structure(**mech)
    assert not b.decomposed and b.mobility == 0 and b.reason


def test_redundant_constraint_sign():
    """q = W0 + Wm - W: a four-bar has none.  The printed '+ W' would give 2."""
    assert S.redundant_constraints(1, 1, 0) == 0
    assert S.redundant_constraints(0, 1, 0) == 1  # double parallelogram
    assert S.redundant_constraints(2, 1, 1) == 0  # cam with roller follower
    w, w0, wm = S.mobility(**FOUR_BAR), 1, 0
    assert w0 + wm + w == 2 != S.redundant_constraints(w, w0, wm)
    with pytest.raises(ValueError):
        S.redundant_constraints(2, 1, 0)


def test_cam_with_roller_local_mobility():
    cam = dict(
        links=["0", "cam", "roller", "follower"],
        frame="0",
        joints=[
            R("O", "0", "cam"),
            ("K", "higher", ("cam", "roller")),
            R("Q", "roller", "follower"),
            P("G", "follower", "0"),
        ],
    )
    assert S.mobility(**cam) == 2 == numeric_mobility(cam)  # the roller's spin is one of them
    a = S.analyse_structure(**cam, local_mobilities=1)
    assert a.higher_pairs == 1 and a.mobility == 1 and a.redundant_constraints == 0
    assert not a.decomposed and "higher" in a.reason


def test_groups_come_off_farthest_first_and_attach_in_link_order():
    """Dyads (2, 3) and (6, 7) hang on the crank, (4, 5) on rocker 3: (4, 5) is farthest and comes
    off first; (2, 3) and (6, 7) are equally near, so they attach in the order they are numbered."""
    mech = dict(
        links=[str(i) for i in range(8)],
        frame="0",
        joints=[
            R("A", "0", "1"),
            R("B", "1", "2"),
            R("C", "2", "3"),
            R("D", "3", "0"),
            R("E", "3", "4"),
            R("F", "4", "5"),
            R("G", "5", "0"),
            R("H", "1", "6"),
            R("I", "6", "7"),
            R("K", "7", "0"),
        ],
    )
    a = S.analyse_structure(**mech)
    assert [g.links for g in a.groups] == [("2", "3"), ("6", "7"), ("4", "5")]


def test_zero_count_with_a_loose_part_is_not_a_group():
    """Link x pinned to the frame twice (over-constrained) carries link y on one pin (free to
    spin): {x, y} counts 3*2 - 2*3 = 0 but is no Assur group; the kinematics shows W = 2."""
    mech = dict(
        links=["0", "1", "2", "3", "x", "y"],
        frame="0",
        joints=FOUR_BAR["joints"] + [R("X1", "0", "x"), R("X2", "x", "0"), R("Y", "x", "y")],
    )
    assert S.mobility(**mech) == 1 and numeric_mobility(mech) == 2
    a = S.analyse_structure(**mech)
    assert not a.decomposed and "x" in a.reason and "y" in a.reason


# --------------------------------------------------------------------------- built from known dyads
DYAD_KINDS = ["RRR", "RRP", "RPR", "PRR", "PRP", "RPP", "PPR"]


@st.composite
def dyad_chains(draw):
    drivers = draw(st.integers(1, 2))
    links, joints, groups = ["0"], [], []
    for i in range(drivers):
        name = f"d{i}"
        links.append(name)
        joints.append((f"J{name}", draw(st.sampled_from(["revolute", "prismatic"])), ("0", name)))
    for k in range(draw(st.integers(1, 4))):
        a, b = f"g{k}a", f"g{k}b"
        kinds = draw(st.sampled_from(DYAD_KINDS))
        to_a = draw(st.sampled_from(links))
        to_b = draw(st.sampled_from(links))
        links += [a, b]
        names = {"R": "revolute", "P": "prismatic"}
        joints += [
            (f"L{k}a", names[kinds[0]], (to_a, a)),
            (f"I{k}", names[kinds[1]], (a, b)),
            (f"L{k}b", names[kinds[2]], (b, to_b)),
        ]
        groups.append((a, b))
    # drivers first in the input, as the textbook numbers them; shuffle nothing else
    return {"links": links, "frame": "0", "joints": joints}, groups, drivers


# ~7 ms each; 60 chains of 1-4 dyads of the three kinds
@settings(max_examples=60)
@given(dyad_chains())
def test_decomposition_recovers_the_dyads_it_was_built_from(built):
    mech, groups, drivers = built
    a = S.analyse_structure(**mech)
    assert a.formula_mobility == drivers == numeric_mobility(mech)
    assert a.decomposed, a.reason
    assert a.drivers == tuple(f"d{i}" for i in range(drivers))
    assert {frozenset(g.links) for g in a.groups} == {frozenset(g) for g in groups}
    assert all(g.group_class == 2 and g.order == 2 and g.dyad_type for g in a.groups)
    # attachment order: a group only leans on drivers, the frame and groups attached before it
    known = {"0", *a.drivers}
    by_name = {j[0]: j for j in mech["joints"]}
    for g in a.groups:
        for name in g.lead_joints:
            assert set(by_name[name][2]) - set(g.links) <= known
        known |= set(g.links)
    # every group is rigid with everything attached before it held
    present = {x for x in mech["links"] if x != "0"}
    for g in reversed(a.groups):
        assert group_is_rigid(mech, g.links, present)
        present -= set(g.links)


# --------------------------------------------------------------------------- validation
@pytest.mark.parametrize(
    "kwargs, words",
    [
        (dict(links=["0", "1", "1"], frame="0", joints=[]), "more than once"),
        (dict(links=["0", "1"], frame="9", joints=[R("A", "0", "1")]), "frame"),
        (dict(links=["0", "1"], frame="0", joints=[("A", "spherical", ("0", "1"))]), "kind"),
        (dict(links=["0", "1"], frame="0", joints=[R("A", "0")]), "at least two"),
        (dict(links=["0", "1"], frame="0", joints=[R("A", "0", "7")]), "unknown link"),
        (dict(links=["0", "1"], frame="0", joints=[R("A", "0", "0")]), "twice"),
        (dict(links=["0", "1", "2"], frame="0", joints=[R("A", "0", "1")]), "not connected"),
        (dict(links=["0", "1"], frame="0", joints=[R("A", "0", "1"), R("A", "0", "1")]), "more than once"),
        (dict(links=["0", "1"], frame="0", joints=["A"]), "joint"),
        (dict(links=["0", "1"], frame="0", joints=[{"name": "A", "links": ["0", "1"]}]), "kind"),
    ],
)
def test_invalid_input_raises_one_sentence(kwargs, words):
    with pytest.raises(ValueError) as err:
        S.mobility(**kwargs)
    message = str(err.value)
    assert words in message and message.endswith(".") and "\n" not in message


def test_invalid_drivers_and_marks():
    for bad in (dict(drivers="7"), dict(drivers="0"), dict(passive_links=["9"]), dict(local_mobilities=-1)):
        with pytest.raises(ValueError):
            S.analyse_structure(**FOUR_BAR, **bad)
    with pytest.raises(ValueError, match="no Assur decomposition"):
        S.assur_groups(**FOUR_BAR, drivers="2")  # a coupler is not pivoted on the frame
    assert S.assur_groups(**FOUR_BAR, drivers="3")[0].links == ("1", "2")  # the rocker may drive
    assert S.driving_links(**STEPHENSON) == ("1",)


def test_joint_inputs_are_interchangeable():
    as_tuples = S.analyse_structure(**SLIDER_CRANK)
    maps = [{"name": n, "kind": k, "links": ls} for n, k, ls in SLIDER_CRANK["joints"]]
    as_maps = S.analyse_structure(links=SLIDER_CRANK["links"], frame="0", joints=maps)
    as_joints = S.analyse_structure(
        links=SLIDER_CRANK["links"],
        frame="0",
        joints=[S.Joint(n, k, ls) for n, k, ls in SLIDER_CRANK["joints"]],
    )
    assert as_tuples == as_maps == as_joints

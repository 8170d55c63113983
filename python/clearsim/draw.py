"""Pictures of a mechanism: its pose at one time and animations of a run.

Bodies are drawn through the points where joints, clearance joints and force elements attach
(a bar for two points, a plate for more, a block for a slider), ground joints with hatched
supports, drivers and motors with a curved arrow, springs as zigzags, loads as arrows (by their
value at the drawn time: none for a load that is zero then), labels moved apart where they would
overlap (:mod:`clearsim.label_layout`). A
clearance is far too small to see at the mechanism's scale, so each clearance joint is drawn
magnified: the bearing circle, the journal inside it displaced by ``magnify × e`` (e the true
eccentricity), and the factor written beside it. The links themselves stay at their true pose.
"""

from __future__ import annotations

import math
from functools import partial
from pathlib import Path
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _core
from .draw_points import PointMarks, paths_of, widen
from .errors import InputError
from .label_layout import renderer_of, separate

#: Colours of the drawing (colour-blind safe).
BODY_COLOUR = "#0072B2"
GROUND_COLOUR = "0.35"
CLEARANCE_COLOUR = "#D55E00"
FORCE_COLOUR = "#009E73"
DRIVE_COLOUR = "#CC79A7"


def _pose(q: np.ndarray, body: Optional[int]) -> Tuple[np.ndarray, float]:
    if body is None:
        return np.zeros(2), 0.0
    return np.array([q[3 * body], q[3 * body + 1]]), float(q[3 * body + 2])


def _point(q: np.ndarray, body: Optional[int], local: Sequence[float]) -> np.ndarray:
    """Global position of a body-frame point (ground: the point itself)."""
    r, th = _pose(q, body)
    c, s = math.cos(th), math.sin(th)
    x, y = float(local[0]), float(local[1])
    return r + np.array([c * x - s * y, s * x + c * y])


def _attachments(desc: Dict[str, Any]) -> Dict[Optional[int], List[Tuple[float, float]]]:
    """Body-frame points where something attaches, per body (None: ground)."""
    pts: Dict[Optional[int], List[Tuple[float, float]]] = {}

    def add(body: Optional[int], p: Sequence[float]) -> None:
        pts.setdefault(body, [])
        t = (float(p[0]), float(p[1]))
        if all(math.hypot(t[0] - a, t[1] - b) > 1e-9 for a, b in pts[body]):
            pts[body].append(t)

    for j in desc["joints"]:
        add(j["body_a"], j["point_a"])
        add(j["body_b"], j["point_b"])
    for c in desc["clearance_joints"]:
        add(c["bearing_body"], c["bearing_point"])
        add(c["journal_body"], c["journal_point"])
    for p in desc.get("prismatic_clearance_joints", []):
        add(p["slider_body"], (0.0, 0.0))
    for f in desc.get("forces", []):
        if f["kind"] == "spring_damper":
            add(f["body_a"], f["point_a"])
            add(f["body_b"], f["point_b"])
        elif f["kind"] == "force":
            add(f["body"], f["point"])
    return pts


def extent(desc: Dict[str, Any], q: np.ndarray) -> float:
    """Size of the mechanism [m]: the diagonal of its attachment points' bounding box."""
    pts = [_point(q, b, p) for b, ps in _attachments(desc).items() for p in ps]
    pts += [np.array(q[3 * k : 3 * k + 2]) for k in range(len(desc["bodies"]))]
    arr = np.array(pts)
    return float(max(np.hypot(*(arr.max(axis=0) - arr.min(axis=0))), 1e-3))


#: Drawn bearing radius as a fraction of the mechanism's size, and the part of it the
#: magnified clearance takes by default.
BEARING_SIZE = 0.03
CLEARANCE_SHARE = 0.35


def default_magnify(desc: Dict[str, Any], size: float) -> float:
    """A round factor (1, 2, 5 × 10^k, at least 1) that draws the largest clearance at about a
    third of the drawn bearing radius (1 % of the mechanism's size)."""
    cs = [c["clearance"] for c in desc["clearance_joints"]] + [p["clearance"] for p in desc.get("prismatic_clearance_joints", [])]
    if not cs or max(cs) <= 0:
        return 1.0
    raw = CLEARANCE_SHARE * BEARING_SIZE * size / max(cs)
    k = 10 ** math.floor(math.log10(raw))
    return max(1.0, float(max(m * k for m in (1, 2, 5) if m * k <= raw)))


def _load_direction(f: Dict[str, Any], desc: Dict[str, Any], q: np.ndarray, t: Optional[float]) -> Optional[np.ndarray]:
    """The unit direction of an applied force at time ``t`` [s] and pose ``q`` (a table in a
    driver's angle reads the driven body's angle in ``q``); without ``t``, a table's largest
    entry. ``None`` when the force is zero: no arrow."""
    v = np.array([_profile_value(f[c], desc, q, t) for c in ("fx", "fy")])
    n = float(np.hypot(*v))
    return v / n if n > 0 else None


def _profile_value(profile: Dict[str, Any], desc: Dict[str, Any], q: np.ndarray, t: Optional[float]) -> float:
    """A load profile's value (forces.py's entry: a constant or a piecewise-linear table, held at
    its ends, repeated every ``period`` of its variable) at time ``t`` or at the angle of the
    driven body in ``q``; the largest entry when ``t`` is ``None``."""
    if profile["kind"] == "constant":
        return float(profile["value"])
    table = profile["table"]
    xs, ys = np.asarray(table["x"], dtype=float), np.asarray(table["y"], dtype=float)
    if not ys.size:
        return 0.0
    if t is None:
        return float(ys[np.argmax(np.abs(ys))])
    argument = profile.get("argument", {})
    x = float(t)
    if argument.get("kind") == "angle":
        body = _driven_body(desc, argument)
        if body is None:
            return float(ys[np.argmax(np.abs(ys))])
        x = float(q[3 * body + 2])
    period = table.get("period")
    if period:
        x = xs[0] + (x - xs[0]) % float(period)
    return float(np.interp(x, xs, ys))


def _driven_body(desc: Dict[str, Any], argument: Dict[str, Any]) -> Optional[int]:
    """The body index a load table's driver (or motor) turns, from the description."""
    if isinstance(argument.get("body"), int):
        return int(argument["body"])
    name = argument.get("driver")
    for d in list(desc.get("drivers", [])) + [f for f in desc.get("forces", []) if f.get("kind") == "motor"]:
        if d.get("name") == name and isinstance(d.get("body"), int):
            return int(d["body"])
    return None


def _zigzag(a: np.ndarray, b: np.ndarray, width: float, turns: int = 6) -> np.ndarray:
    d = b - a
    n = float(np.hypot(*d))
    if n == 0:
        return np.array([a, b])
    u, v = d / n, np.array([-d[1], d[0]]) / n
    s = np.concatenate([[0.0, 0.15], 0.15 + 0.7 * (np.arange(2 * turns) + 0.5) / (2 * turns), [0.85, 1.0]])
    off = np.concatenate([[0.0, 0.0], width * (-1.0) ** np.arange(2 * turns), [0.0, 0.0]])
    return a + np.outer(s * n, u) + np.outer(off, v)


def _convex_hull(points: np.ndarray) -> np.ndarray:
    pts = sorted(map(tuple, points))
    if len(pts) <= 2:
        return np.array(pts)

    def half(seq: Any) -> List[Any]:
        out: List[Any] = []
        for p in seq:
            while len(out) >= 2 and (out[-1][0] - out[-2][0]) * (p[1] - out[-2][1]) - (out[-1][1] - out[-2][1]) * (p[0] - out[-2][0]) <= 0:
                out.pop()
            out.append(p)
        return out

    lower, upper = half(pts), half(reversed(pts))
    return np.array(lower[:-1] + upper[:-1])


def _rotate(th: float, v: Any) -> np.ndarray:
    c, s = math.cos(th), math.sin(th)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])


def _place_polygon(patch: Any, body: Optional[int], corners: Sequence[Tuple[float, float]], q: np.ndarray) -> None:
    patch.set_xy(np.array([_point(q, body, c) for c in corners]))


def _place_line(line: Any, points: Callable[[np.ndarray], np.ndarray], q: np.ndarray) -> None:
    line.set_data(*points(q).T)


def _place_label(label: Any, points: Callable[[np.ndarray], np.ndarray], q: np.ndarray) -> None:
    label.xy = tuple(points(q).mean(axis=0))


def _place_circle(circle: Any, centre: Callable[[np.ndarray], np.ndarray], q: np.ndarray) -> None:
    circle.set_center(tuple(centre(q)))


def _place_spring(coil: Any, f: Dict[str, Any], width: float, q: np.ndarray) -> None:
    coil.set_data(*_zigzag(_point(q, f["body_a"], f["point_a"]), _point(q, f["body_b"], f["point_b"]), width).T)


def _place_spring_label(label: Any, f: Dict[str, Any], q: np.ndarray) -> None:
    """The spring's name at its middle, set off 10 points to its upper side (clear of the coil)."""
    a, b = _point(q, f["body_a"], f["point_a"]), _point(q, f["body_b"], f["point_b"])
    d = b - a
    n = np.array([-d[1], d[0]]) / max(float(np.hypot(*d)), 1e-300)
    if n[1] < 0 or (n[1] == 0 and n[0] < 0):
        n = -n
    label.xy = tuple(0.5 * (a + b))
    label.xyann = tuple(10.0 * n)
    label.set_horizontalalignment("left" if n[0] > 1e-9 else "right" if n[0] < -1e-9 else "center")
    label.set_verticalalignment("bottom")


def _ground_point(local: Sequence[float], q: np.ndarray) -> np.ndarray:
    return _point(q, None, local)


class Drawing:
    """The artists of one drawing of a mechanism and how each follows the body coordinates q:
    :meth:`update` moves them (``set_data``, ``set_xy``, ``set_center``, ...) without creating
    any, so an animation redraws only these artists over a fixed background (:func:`animate`).
    """

    def __init__(self, ax: Any, desc: Dict[str, Any], q: np.ndarray, mag: float, size: float, labels: bool = True, t: Optional[float] = None) -> None:
        self.ax = ax
        self.desc = desc
        self.artists: List[Any] = []
        #: The labels and the offset [points] each is written at before :meth:`layout` moves it.
        self.labels: List[Tuple[Any, Tuple[float, float]]] = []
        #: Artists labels are moved off (the magnified bearings, point markers).
        self.obstacles: List[Any] = []
        self._updates: List[Callable[[np.ndarray], None]] = []
        self._labels = labels
        self.t = t
        self._bodies(desc, size)
        self._joints(desc, size)
        self._clearance(desc, mag, size)
        self._drives_and_forces(desc, size)
        self.update(np.asarray(q, dtype=float), t)

    def update(self, q: np.ndarray, t: Optional[float] = None) -> None:
        """Move every artist to the pose ``q`` at time ``t`` [s] (a load's arrow shows its value
        then; ``None``: a table load by its largest entry), each label back at its own offset."""
        self.t = t
        for label, offset in self.labels:
            label.xyann = offset
        for up in self._updates:
            up(q)

    def adopt(self, marks: Any) -> None:
        """Lay out the labels of point ``marks`` (:class:`clearsim.draw_points.PointMarks`) with
        the drawing's, every label kept off their markers (a clearance's label off a tool point)."""
        self.labels += [(label, label.xyann) for label in marks.labels]
        self.obstacles += marks.markers

    def layout(self, settle: bool = True) -> None:
        """Move the labels apart where they overlap (:func:`clearsim.label_layout.separate`), in
        the figure's pixels: call it once the axes' limits are set. ``settle``: run the figure's
        layout engine first (and again while labels move: a constrained layout moves the axes);
        an animation's frames, drawn over a frozen layout, do without."""
        if not self.labels:
            return
        fig = self.ax.figure
        renderer = renderer_of(fig)
        engine = fig.get_layout_engine() if settle else None
        if type(engine).__name__ == "PlaceHolderLayoutEngine":  # a layout frozen
            engine = None
        for _ in range(3 if engine is not None else 1):
            if engine is not None:
                engine.execute(fig)
            self.ax.apply_aspect()
            if not separate([label for label, _ in self.labels], renderer, fig.dpi, self.obstacles):
                break

    # ------------------------------------------------------------------ artists
    def _add(self, artist: Any) -> Any:
        self.artists.append(artist)
        return artist

    def _patch(self, patch: Any) -> Any:
        return self._add(self.ax.add_patch(patch))

    def _line(self, **style: Any) -> Any:
        return self._add(self.ax.plot([], [], **style)[0])

    def _label(self, text: str, offset: Tuple[float, float], colour: str, **kw: Any) -> Any:
        if not self._labels:
            return None
        label = self._add(self.ax.annotate(text, (0.0, 0.0), xytext=offset, textcoords="offset points", fontsize=7, color=colour, zorder=6, **kw))
        self.labels.append((label, offset))
        return label

    def _polygon(self, **style: Any) -> Any:
        from matplotlib import patches

        return self._patch(patches.Polygon(np.zeros((3, 2)), closed=True, **style))

    def _support(self, where: Callable[[np.ndarray], np.ndarray], r: float) -> None:
        """A hatched ground support under the point ``where(q)``."""
        tri = self._polygon(facecolor="none", edgecolor=GROUND_COLOUR, lw=1.0, hatch="////", zorder=1)

        def place(q: np.ndarray) -> None:
            p = where(q)
            tri.set_xy(np.array([p, p + [-1.6 * r, -2.4 * r], p + [1.6 * r, -2.4 * r]]))

        self._updates.append(place)

    # ------------------------------------------------------------------ elements
    def _bodies(self, desc: Dict[str, Any], size: float) -> None:
        att = _attachments(desc)
        names = [b["name"] for b in desc["bodies"]]
        slider = {j["body_b"] for j in desc["joints"] if j["kind"] == "prismatic"} | {p["slider_body"] for p in desc.get("prismatic_clearance_joints", [])}
        block = 0.06 * size
        for k in range(len(names)):
            local = att.get(k, [])

            def pts(q: np.ndarray, k: int = k, local: List[Tuple[float, float]] = local) -> np.ndarray:
                return np.array([_point(q, k, p) for p in local] or [q[3 * k : 3 * k + 2]])

            if k in slider or len(local) <= 1:
                corners = np.array([[-block / 2, -block / 3], [block / 2, -block / 3], [block / 2, block / 3], [-block / 2, block / 3]])
                box = self._polygon(facecolor="#cfe3f3", edgecolor=BODY_COLOUR, lw=1.5, zorder=2)
                self._updates.append(partial(_place_polygon, box, k, [tuple(c) for c in corners]))
            if len(local) == 2 or (len(local) > 2 and k in slider):
                bar = self._line(color=BODY_COLOUR, lw=3.0, solid_capstyle="round", zorder=2)
                self._updates.append(partial(_place_line, bar, pts))
            elif len(local) > 2:
                hull = [tuple(p) for p in _convex_hull(np.array(local))]  # a rigid motion keeps the hull
                plate = self._polygon(facecolor="#cfe3f3", edgecolor=BODY_COLOUR, lw=2, alpha=0.9, zorder=2)
                self._updates.append(partial(_place_polygon, plate, k, hull))
            label = self._label(names[k], (4, 4), BODY_COLOUR)
            if label is not None:
                self._updates.append(partial(_place_label, label, pts))

    def _joints(self, desc: Dict[str, Any], size: float) -> None:
        from matplotlib import patches

        pin = 0.012 * size
        block = 0.06 * size
        for j in desc["joints"]:
            if j["kind"] == "revolute":

                def at(q: np.ndarray, j: Dict[str, Any] = j) -> np.ndarray:
                    return _point(q, j["body_b"], j["point_b"])

                circle = self._patch(patches.Circle((0.0, 0.0), pin, facecolor="white", edgecolor="black", lw=1.2, zorder=4))
                self._updates.append(partial(_place_circle, circle, at))
                if j["body_a"] is None or j["body_b"] is None:
                    self._support(at, pin)
                continue
            # prismatic: the guide along its axis through the ground/guide point, two rails beside the slider
            rails = [self._line(color=GROUND_COLOUR, lw=1.0, zorder=1) for _ in (-1, 1)]
            guide = self._line(color=GROUND_COLOUR, lw=0.8, ls="--", zorder=1)

            def prismatic(q: np.ndarray, j: Dict[str, Any] = j, rails: List[Any] = rails, guide: Any = guide) -> None:
                _, th = _pose(q, j["body_a"])
                u = _rotate(th, np.asarray(j["axis"], dtype=float))
                u = u / max(float(np.hypot(*u)), 1e-300)
                slider = np.array(q[3 * j["body_b"] : 3 * j["body_b"] + 2])
                base = _point(q, j["body_a"], j["point_a"])
                along = float(np.dot(slider - base, u))
                n = np.array([-u[1], u[0]])
                for rail, side in zip(rails, (-1, 1)):
                    off = side * block / 3 * 1.15 * n
                    rail.set_data(*np.array([slider + off - 0.8 * block * u, slider + off + 0.8 * block * u]).T)
                guide.set_data(*np.array([base + (along - 0.35 * size) * u, base + (along + 0.35 * size) * u]).T)

            self._updates.append(prismatic)

    def _clearance(self, desc: Dict[str, Any], mag: float, size: float) -> None:
        from matplotlib import patches

        r_draw = BEARING_SIZE * size
        for c in desc["clearance_joints"]:
            ring = mag * c["clearance"]
            rb = max(r_draw, ring / 0.6)  # a large magnification draws a larger bearing
            bearing = self._patch(patches.Circle((0.0, 0.0), rb, facecolor="white", edgecolor=CLEARANCE_COLOUR, lw=1.5, zorder=4))
            self.obstacles.append(bearing)
            journal = self._patch(patches.Circle((0.0, 0.0), rb - ring, facecolor="#f6d5bf", edgecolor=CLEARANCE_COLOUR, lw=1.0, zorder=5))
            label = self._label(f"{c['name']} (c = {c['clearance'] * 1e3:.3g} mm, ×{mag:g})", (6, -10), CLEARANCE_COLOUR)

            def centre(q: np.ndarray, c: Dict[str, Any] = c) -> np.ndarray:
                return _point(q, c["bearing_body"], c["bearing_point"])

            def magnified(q: np.ndarray, c: Dict[str, Any] = c, bearing: Any = bearing, journal: Any = journal, label: Any = label) -> None:
                b = _point(q, c["bearing_body"], c["bearing_point"])  # this joint's (not the loop's last ``centre``)
                e = _point(q, c["journal_body"], c["journal_point"]) - b
                bearing.set_center(tuple(b))
                journal.set_center(tuple(b + mag * e))
                if label is not None:
                    label.xy = tuple(b)

            self._updates.append(magnified)
            if c["bearing_body"] is None:
                self._support(centre, r_draw)
        block = 0.06 * size
        for p in desc.get("prismatic_clearance_joints", []):
            walls = [self._line(color=CLEARANCE_COLOUR, lw=1.2, zorder=1) for _ in (-1, 1)]
            label = self._label("", (0, 6), CLEARANCE_COLOUR)

            def play(q: np.ndarray, p: Dict[str, Any] = p, walls: List[Any] = walls, label: Any = label) -> None:
                slider = np.array(q[3 * p["slider_body"] : 3 * p["slider_body"] + 2])
                _, th = _pose(q, p["guide_body"])
                u = _rotate(th, np.asarray(p["axis"], dtype=float))
                u = u / max(float(np.hypot(*u)), 1e-300)
                n = np.array([-u[1], u[0]])
                base = _point(q, p["guide_body"], p["guide_point"])
                lateral = float(np.dot(slider - base, n))
                half = block / 3 + mag * p["clearance"]
                along = float(np.dot(slider - base, u))
                for wall, side in zip(walls, (-1, 1)):
                    wall.set_data(*np.array([base + (along - 0.35 * size) * u + side * half * n, base + (along + 0.35 * size) * u + side * half * n]).T)
                if label is not None:
                    label.xy = tuple(base + along * u + half * n)
                    label.set_text(f"{p['name']} (play {p['clearance'] * 1e3:.3g} mm, offset ×{mag:.0f}: {lateral * 1e6:.0f} µm)")

            self._updates.append(play)

    def _drives_and_forces(self, desc: Dict[str, Any], size: float) -> None:
        from matplotlib import patches

        pin = 0.012 * size
        # Drivers and motors: a curved arrow at the driven body's centroid.
        driven = [(d["body"], d["name"]) for d in desc["drivers"]] + [(f["body"], f["name"]) for f in desc.get("forces", []) if f["kind"] in ("motor", "torque")]
        for body, name in driven:
            arrow = self._patch(patches.FancyArrowPatch((0, 0), (1, 1), connectionstyle="arc3,rad=0.5", arrowstyle="-|>", mutation_scale=9, color=DRIVE_COLOUR, lw=1.2, zorder=6))
            label = self._label(name, (2, 2), DRIVE_COLOUR)

            def drive(q: np.ndarray, body: Optional[int] = body, arrow: Any = arrow, label: Any = label) -> None:
                r, _ = _pose(q, body)
                arrow.set_positions(tuple(r + [0.045 * size, 0]), tuple(r + [0, 0.045 * size]))
                if label is not None:
                    label.xy = tuple(r + [0.03 * size, 0.03 * size])

            self._updates.append(drive)
        # Springs and loads.
        for f in desc.get("forces", []):
            if f["kind"] == "spring_damper":
                coil = self._line(color=FORCE_COLOUR, lw=1.2, zorder=3)
                self._updates.append(partial(_place_spring, coil, f, 0.015 * size))
                label = self._label(f["name"], (0, 0), FORCE_COLOUR)
                if label is not None:
                    self._updates.append(partial(_place_spring_label, label, f))
                if f["body_a"] is None:
                    self._support(partial(_ground_point, f["point_a"]), pin)
            elif f["kind"] == "force":
                arrow = self._patch(patches.FancyArrowPatch((0, 0), (1, 1), arrowstyle="-|>", mutation_scale=10, color=FORCE_COLOUR, lw=1.5, zorder=6))
                label = self._label(f["name"], (3, 3), FORCE_COLOUR)

                def load(q: np.ndarray, f: Dict[str, Any] = f, arrow: Any = arrow, label: Any = label) -> None:
                    p = _point(q, f["body"], f["point"])
                    u = _load_direction(f, self.desc, q, self.t)
                    arrow.set_visible(u is not None)  # a load that is zero then draws nothing
                    if label is not None:
                        label.set_visible(u is not None)
                    if u is None:
                        return
                    if f.get("frame") == "body":
                        u = _rotate(_pose(q, f["body"])[1], u)
                    tail = p - 0.12 * size * u
                    arrow.set_positions(tuple(tail), tuple(p))
                    if label is not None:
                        label.xy = tuple(tail)

                self._updates.append(load)


def _indexed(desc: Dict[str, Any]) -> Dict[str, Any]:
    """``desc`` as the core reads it (bodies by index, the ground ``None``: ``_core.resolve``),
    which the drawing places by the coordinates q."""
    return dict(_core.resolve(desc))


def draw(ax: Any, desc: Dict[str, Any], q: np.ndarray, *, magnify: Optional[float] = None, size: Optional[float] = None, labels: bool = True, t: Optional[float] = None) -> float:
    """Draw the mechanism ``desc`` (a :meth:`Mechanism.description`) at coordinates ``q`` on
    ``ax`` at time ``t`` [s] (loads drawn by their value then: none for a zero load), labels
    moved apart where they overlap at the axes' present limits. Returns the clearance
    magnification used."""
    mag, drawing = _draw(ax, _indexed(desc), q, magnify, size, labels, t)
    ax.autoscale_view()
    drawing.layout()
    return mag


def _draw(ax: Any, desc: Dict[str, Any], q: np.ndarray, magnify: Optional[float], size: Optional[float], labels: bool, t: Optional[float]) -> Tuple[float, Drawing]:
    q = np.asarray(q, dtype=float)
    size = size or extent(desc, q)
    mag = float(magnify) if magnify is not None else default_magnify(desc, size)
    drawing = Drawing(ax, desc, q, mag, size, labels, t)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    if t is not None:
        ax.set_title(f"t = {t:.4f} s", fontsize=9)
    return mag, drawing


def _limits(desc: Dict[str, Any], qs: np.ndarray) -> Tuple[Tuple[float, float], Tuple[float, float]]:
    pts = []
    for q in qs:
        pts += [_point(q, b, p) for b, ps in _attachments(desc).items() for p in ps]
        pts += [np.array(q[3 * k : 3 * k + 2]) for k in range(len(desc["bodies"]))]
    arr = np.array(pts)
    lo, hi = arr.min(axis=0), arr.max(axis=0)
    span = float(np.hypot(*(hi - lo)) or 1.0)
    pad = 0.12 * span
    # Keep the frame at least half as high as wide (and the reverse): flat poses stay readable.
    half = np.maximum(0.5 * (hi - lo) + pad, 0.25 * span)
    mid = 0.5 * (hi + lo)
    return (mid[0] - half[0], mid[0] + half[0]), (mid[1] - half[1], mid[1] + half[1])


def plot_pose(
    desc: Dict[str, Any], q: np.ndarray, *, magnify: Optional[float] = None, title: Optional[str] = None, t: Optional[float] = None, ax: Any = None,
    marks: Optional[Callable[[Any], Any]] = None,
) -> Any:  # fmt: skip
    """A figure of the mechanism at coordinates ``q`` (see :func:`draw`); ``marks(ax)`` adds
    point marks (:class:`clearsim.draw_points.PointMarks`) once the limits are set, whose labels
    and markers the labels' layout then keeps clear of."""
    from . import plots

    desc = _indexed(desc)
    with plots.style():
        if ax is None:
            fig = plots.new_figure(6.0, 5.0)
            ax = fig.add_subplot(1, 1, 1)
        else:
            fig = ax.figure
        _, drawing = _draw(ax, desc, q, magnify, None, True, t)
        (x0, x1), (y0, y1) = _limits(desc, np.asarray(q)[None, :])
        ax.set_xlim(x0, x1)
        ax.set_ylim(y0, y1)
        if marks is not None:
            drawing.adopt(marks(ax))
        drawing.layout()  # at the limits the picture is drawn with
        if title:
            ax.set_title(title if t is None else f"{title}, t = {t:.4f} s", fontsize=9)
    return fig


def states_at(result: Any, times: np.ndarray) -> np.ndarray:
    """Body coordinates q at ``times`` [s], interpolated linearly between the stored outputs
    (angles unwrapped first)."""
    q = result._channel("q", "states")
    t = result.t
    times = np.asarray(times, dtype=float)
    if times.size and not np.all(np.isfinite(times)):
        bad = float(times[~np.isfinite(times)][0])
        raise InputError(f"invalid t = {bad!r}: must be a finite time [s] in the run, which covers [{t[0]:g}, {t[-1]:g}] s", field="t", value=bad)
    if times.size and (times.min() < t[0] - 1e-12 or times.max() > t[-1] + 1e-12):
        bad = float(times.min() if times.min() < t[0] - 1e-12 else times.max())
        raise InputError(f"invalid t = {bad:g} s: outside the run, which covers [{t[0]:g}, {t[-1]:g}] s", field="t", value=bad)
    return np.column_stack([np.interp(times, t, q[:, k]) for k in range(q.shape[1])])


def animate(
    result: Any, path: Union[str, Path], *, speed: float = 1.0, magnify: Optional[float] = None, fps: int = 25, t_start: Optional[float] = None, t_end: Optional[float] = None,
    max_frames: int = 400, dpi: int = 100, orbits: bool = True, points: Sequence[Any] = (),
) -> Path:  # fmt: skip
    """Animate a run: the mechanism at ``speed`` × real time (``speed=0.05``: twenty times
    slower), clearances magnified, with each revolute clearance joint's journal orbit (e/c, the
    clearance circle) in an inset. ``path`` ending in ``.gif`` (Pillow) or ``.mp4`` (needs
    ffmpeg). At most ``max_frames`` frames: longer runs are sampled more coarsely. ``points``
    (:class:`clearsim.points.TrackedPoint`) are marked and trace their path as the run goes."""

    import matplotlib.animation as animation

    from . import plots

    if result.description is None:
        raise InputError("invalid result: it does not carry its mechanism (make it with Mechanism.simulate)", field="result", value=None)
    desc = _indexed(result.description)
    path = Path(path)
    if path.suffix.lower() not in (".gif", ".mp4"):
        raise InputError(f"invalid path = {str(path)!r}: must end in .gif or .mp4", field="path", value=str(path))
    if not speed > 0:
        raise InputError(f"invalid speed = {speed!r}: must be positive (1 = real time)", field="speed", value=speed)
    if path.suffix.lower() == ".mp4" and not animation.writers.is_available("ffmpeg"):
        raise InputError("invalid path: writing .mp4 needs ffmpeg on the PATH; write a .gif instead", field="path", value=str(path))
    t0 = result.t[0] if t_start is None else float(t_start)
    t1 = result.t[-1] if t_end is None else float(t_end)
    n = int(min(max_frames, max(2, math.ceil((t1 - t0) / speed * fps))))
    times = np.linspace(t0, t1, n)
    qs = states_at(result, times)
    size = extent(desc, qs[0])
    mag = float(magnify) if magnify is not None else default_magnify(desc, size)
    joints = [c for c in desc["clearance_joints"]] if orbits else []
    xlim, ylim = _limits(desc, qs[:: max(1, n // 50)])
    with plots.style():
        fig = plots.new_figure(7.5 if joints else 6.0, 5.0)
        if joints:
            gs = fig.add_gridspec(len(joints), 2, width_ratios=[3, 1])
            ax = fig.add_subplot(gs[:, 0])
            insets = [fig.add_subplot(gs[k, 1]) for k in range(len(joints))]
        else:
            ax = fig.add_subplot(1, 1, 1)
            insets = []
        # Orbits from every stored output (not only the frames), drawn up to each frame's time.
        q_all = result._channel("q", "states")
        orbit = []
        for c in joints:
            b = np.array([_point(q, c["bearing_body"], c["bearing_point"]) for q in q_all])
            j = np.array([_point(q, c["journal_body"], c["journal_point"]) for q in q_all])
            orbit.append((j - b) / c["clearance"])
        upto = np.searchsorted(result.t, times, side="right")
        # The background (axes, ticks, labels, clearance circles of the insets) is drawn once;
        # each frame moves the mechanism's artists, the orbits and the time label and redraws
        # only them over it (blitting).
        drawing = Drawing(ax, desc, qs[0], mag, size, t=float(times[0]))
        ax.set_aspect("equal")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.set_xlim(*xlim)
        ax.set_ylim(*ylim)
        clock = ax.set_title(f"t = {times[0]:.4f} s", fontsize=9)
        marks = PointMarks(ax, result.body_names, points, paths_of(result, points)) if points else None
        if marks is not None:
            marks.update(qs[0])
            widen(ax, marks.extent(qs[0]))
            drawing.adopt(marks)
        moving: List[Any] = drawing.artists + (marks.artists if marks is not None else []) + [clock]
        traces = []
        for k, (axi, c) in enumerate(zip(insets, joints)):
            th = np.linspace(0, 2 * math.pi, 120)
            axi.plot(np.cos(th), np.sin(th), color="0.5", lw=0.8)
            trace = axi.plot([], [], color=CLEARANCE_COLOUR, lw=0.8)[0]
            dot = axi.plot([], [], "o", color=CLEARANCE_COLOUR, ms=4)[0]
            traces.append((trace, dot))
            moving += [trace, dot]
            lim = max(1.1, float(np.abs(orbit[k]).max()) * 1.05)
            axi.set_xlim(-lim, lim)
            axi.set_ylim(-lim, lim)
            axi.set_aspect("equal")
            axi.set_title(f"{c['name']}: e/c", fontsize=8)
            axi.tick_params(labelsize=6)

        def frame(i: int) -> None:
            drawing.update(qs[i], float(times[i]))
            if marks is not None:
                marks.update(qs[i], int(upto[i]))
            drawing.layout(settle=False)
            clock.set_text(f"t = {times[i]:.4f} s")
            for k, (trace, dot) in enumerate(traces):
                o = orbit[k][: max(1, upto[i])]
                trace.set_data(o[:, 0], o[:, 1])
                dot.set_data(o[-1:, 0], o[-1:, 1])

        path.parent.mkdir(parents=True, exist_ok=True)
        if path.suffix.lower() == ".gif":
            _write_gif(fig, moving, frame, n, path, fps, dpi)
        else:
            def redraw(i: int) -> List[Any]:
                frame(i)
                return []

            anim = animation.FuncAnimation(fig, redraw, frames=n, blit=False)
            anim.save(str(path), writer=animation.FFMpegWriter(fps=fps), dpi=dpi)
    return path


def _write_gif(fig: Any, moving: List[Any], frame: Callable[[int], None], n: int, path: Path, fps: int, dpi: int) -> None:
    """Render ``n`` frames by blitting: the figure without the ``moving`` artists once, then per
    frame ``frame(i)`` and only those artists over a copy of it; written with Pillow."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from PIL import Image

    fig.set_dpi(dpi)
    canvas = FigureCanvasAgg(fig)
    for a in moving:
        a.set_animated(True)
    frame(0)
    canvas.draw()  # the layout, and the background without the moving artists
    fig.set_layout_engine("none")  # keep that layout: the frames redraw no axes
    background = canvas.copy_from_bbox(fig.bbox)
    images = []
    palette: Any = None
    for i in range(n):
        frame(i)
        canvas.restore_region(background)
        for a in moving:
            fig.draw_artist(a)
        rgb = Image.frombuffer("RGBA", canvas.get_width_height(), bytes(canvas.buffer_rgba()), "raw", "RGBA", 0, 1).convert("RGB")
        # One palette for every frame (the first frame's, which shows every colour used): no
        # flicker between frames, and mapping to it is cheaper than a new palette per frame.
        if palette is None:
            palette = rgb.quantize(colors=255, method=Image.Quantize.MEDIANCUT)
        images.append(rgb.quantize(palette=palette, dither=Image.Dither.NONE))
    images[0].save(path, save_all=True, append_images=images[1:], duration=round(1000 / fps), loop=0, disposal=1)

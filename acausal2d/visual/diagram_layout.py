"""Layered layout of a model diagram (Sugiyama, Tagawa and Toda 1981):
layers that follow the flow of power, few crossings, no overlapping boxes.

1. Direction: power enters at the prime movers (motors, sources with no
   input, else signal-driven sources, else the ground) and spreads along
   the mechanical, band and hydraulic connections (breadth first); a signal
   runs from its output to its input.  The few edges that close a cycle
   against that order are turned round for the layering only.
2. Layers: the longest path from the sources; a box that only feeds others
   sits just before the first of them.  A connection over several layers
   runs through a point per layer between.
3. Order within a layer: barycentre sweeps (down and up) keeping the order
   with the fewest crossings.
4. Positions: the boxes of a layer stacked in that order, each as close to
   the mean height of its neighbours as the stacking allows (least squares
   under the no-overlap constraints, by pool-adjacent-violators).

Everything here is pure Python (no graph library: networkx's import alone
took longer than drawing a model); the result is a
:class:`Layout` that :mod:`acausal2d.visual.diagram_svg` draws.
"""
from collections import deque
from dataclasses import dataclass, field

import bisect

CHAR = 6.4            # width of a character of the box texts (11 px sans-serif), px
SMALL = 5.0           # of the port names (9 px)
HEAD = 22             # the name line
GLYPH = 38            # the symbol
PARAM = 13            # one parameter line
PORT_STEP = 20        # between two ports on one side
LAYER_GAP = 120       # between two columns of boxes
BOX_GAP = 26          # between two boxes of a column
DUMMY_GAP = 10        # between lines passing a column
MARGIN = 40
SWEEPS = 12


@dataclass
class Layout:
    """Where everything goes: ``boxes`` {path: (x, y, w, h)}, ``ports``
    {(box, port): (x, y, side)}, ``routes`` [list of (x, y) per line, in the
    order of the structure's lines], the size ``width`` x ``height`` and
    ``layers`` (box paths per column, in order)."""
    boxes: dict
    ports: dict
    routes: list
    width: float
    height: float
    layers: list = field(default_factory=list)


def box_size(box):
    """(width, height) of a box: its texts and its ports (by side, once
    the sides are set)."""
    if box.external:
        return max(60.0, CHAR * len(box.name) + 34), 30.0
    def on(side):
        return [p for p in box.ports.values() if p.side == side or p.mirror]
    n_left, n_right = len(on("left")), len(on("right"))
    label = lambda side: max([SMALL * len(p.name) for p in on(side)] or [0])  # noqa: E731
    text = max([CHAR * (len(box.name) + 2)] + [CHAR * 0.92 * len(t) for t in box.params])
    side = max(label("left"), label("right"))      # the texts are centred between the names
    width = max(110.0, text + 2 * side + 24, 2 * side + 70)
    body = HEAD + GLYPH + PARAM * len(box.params) + 10
    return width, float(max(body, PORT_STEP * (max(n_left, n_right) + 1) + HEAD / 2))


# ------------------------------------------------------------ 1. direction
_REFERENCES = ("PressureSource",)     # a tank: a reference, not where power comes from


def _roots(st, nodes, power):
    """The boxes power enters at, per connected part of the power graph:
    motors and sources with no input, else sources driven by a signal,
    else the ground (a fixed point, the world, a tank), else the first."""
    driven = {ln.box_b for ln in st.lines if ln.domain == "signal"}
    boxes = {b.path: b for b in st.boxes}
    def source(p):
        return boxes[p].kind == "source" and boxes[p].cls not in _REFERENCES
    tests = [lambda p: boxes[p].cls == "AsyncMotor" or source(p) and p not in driven, source,
             lambda p: boxes[p].kind in ("fixed", "world") or boxes[p].cls in _REFERENCES]
    roots = []
    for part in _components(nodes, power):
        cand = next((c for c in ([p for p in part if t(p)] for t in tests) if c), None)
        roots += cand or [part[0]]
    return roots


def _components(nodes, adjacent):
    """The connected parts of an undirected graph ({node: neighbours}),
    each in the order of ``nodes``."""
    order = {v: i for i, v in enumerate(nodes)}
    seen, parts = set(), []
    for start in nodes:
        if start in seen:
            continue
        seen.add(start)
        part, todo = [], [start]
        while todo:
            v = todo.pop()
            part.append(v)
            new = [w for w in adjacent[v] if w not in seen]
            seen.update(new)
            todo += new
        parts.append(sorted(part, key=order.__getitem__))
    return parts


def _distances(st):
    """Breadth-first distance of each box from the roots along power lines."""
    nodes = [b.path for b in st.boxes]
    order = {p: i for i, p in enumerate(nodes)}
    power = {p: set() for p in nodes}
    for ln in st.lines:
        if ln.domain != "signal" and ln.box_a != ln.box_b:
            power[ln.box_a].add(ln.box_b)
            power[ln.box_b].add(ln.box_a)
    roots = _roots(st, nodes, power)
    dist = {r: 0 for r in roots}
    todo = deque(roots)
    while todo:
        v = todo.popleft()
        for w in sorted(power[v], key=order.__getitem__):
            if w not in dist:
                dist[w] = dist[v] + 1
                todo.append(w)
    return dist


def _directed(st):
    """The DAG the layers follow ({node: successors}): power lines from
    nearer the roots to farther, signals from output to input, cycles
    broken."""
    order = {b.path: i for i, b in enumerate(st.boxes)}
    dist = _distances(st)
    rank = {p: (dist.get(p, 0), order[p]) for p in order}
    dag = {p: [] for p in order}
    for ln in st.lines:
        a, b = ln.box_a, ln.box_b
        if a == b:
            continue
        if ln.domain != "signal" and rank[a] > rank[b]:
            a, b = b, a
        if a not in dag[b] and b not in dag[a]:
            dag[a].append(b)
    while True:
        cycle = _find_cycle(dag)
        if cycle is None:
            return dag
        u, v = max(cycle, key=lambda e: (rank[e[0]] > rank[e[1]], rank[e[0]]))
        dag[u].remove(v)
        if u not in dag[v]:
            dag[v].append(u)


def _find_cycle(dag):
    """The edges of a cycle of ``dag`` ({node: successors}), or None:
    depth first from the nodes in their order."""
    state = {}                       # 1: on the current path, 2: done
    for start in dag:
        if start in state:
            continue
        path, stack = [start], [iter(dag[start])]
        state[start] = 1
        while stack:
            for w in stack[-1]:
                if state.get(w) == 1:
                    loop = path[path.index(w):] + [w]
                    return list(zip(loop[:-1], loop[1:]))
                if w not in state:
                    state[w] = 1
                    path.append(w)
                    stack.append(iter(dag[w]))
                    break
            else:
                state[path.pop()] = 2
                stack.pop()
    return None


def _topological(dag):
    """The nodes of the acyclic ``dag`` ({node: successors}), each after
    its predecessors."""
    indegree = {v: 0 for v in dag}
    for v in dag:
        for w in dag[v]:
            indegree[w] += 1
    todo = deque(v for v in dag if indegree[v] == 0)
    out = []
    while todo:
        v = todo.popleft()
        out.append(v)
        for w in dag[v]:
            indegree[w] -= 1
            if indegree[w] == 0:
                todo.append(w)
    return out


# ------------------------------------------------------------ 2. layers
def _layers(dag):
    """{node: layer}: longest path; a node that only feeds others moves
    up to just before the first of them."""
    pred = {v: [] for v in dag}
    for v in dag:
        for w in dag[v]:
            pred[w].append(v)
    order = _topological(dag)
    layer = {}
    for v in order:
        layer[v] = max((layer[u] + 1 for u in pred[v]), default=0)
    for v in reversed(order):
        if dag[v] and not pred[v]:
            layer[v] = min(layer[w] for w in dag[v]) - 1
    low = min(layer.values(), default=0)
    return {v: k - low for v, k in layer.items()}


def _chains(st, layer):
    """Per line, the nodes it passes from its first box to its second:
    the two boxes and a dummy per layer between."""
    chains = []
    for i, ln in enumerate(st.lines):
        a, b = ln.box_a, ln.box_b
        la, lb = layer[a], layer[b]
        step = 1 if lb >= la else -1
        chains.append([a] + [("dummy", i, k) for k in range(la + step, lb, step)] + [b])
    return chains


# ------------------------------------------------------------ 3. order
def _crossings(upper, lower, edges):
    """Crossings between two adjacent layers (``edges`` between them, upper
    end first): pairs of edges whose ends are in opposite orders, counted
    by bisection over the lower ends of the edges from earlier upper
    nodes."""
    pos_u = {v: i for i, v in enumerate(upper)}
    pos_l = {v: i for i, v in enumerate(lower)}
    pairs = sorted((pos_u[a], pos_l[b]) for a, b in edges)
    seen, count, k = [], 0, 0
    while k < len(pairs):
        group = [lo for u, lo in pairs[k:] if u == pairs[k][0]]
        count += sum(len(seen) - bisect.bisect_right(seen, lo) for lo in group)
        for lo in group:
            bisect.insort(seen, lo)
        k += len(group)
    return count


def _sweep(layers, neighbours, down):
    """One barycentre sweep: each layer ordered by the mean position of
    its neighbours in the layer before it (in the sweep's direction)."""
    idx = range(1, len(layers)) if down else range(len(layers) - 2, -1, -1)
    for i in idx:
        ref = {v: k for k, v in enumerate(layers[i - 1 if down else i + 1])}
        def key(item):
            k, v = item
            near = [ref[u] for u in neighbours[v] if u in ref]
            return (sum(near) / len(near) if near else k, k)
        layers[i] = [v for _, v in sorted(enumerate(layers[i]), key=key)]


def _transpose(layers, edges, rounds=4):
    """Swap neighbours within a layer while that lowers the crossings with
    the layers on both sides (the transposition step of Gansner et al.
    1993)."""
    def local(i):
        return sum(_crossings(layers[j], layers[j + 1], edges[j])
                   for j in (i - 1, i) if 0 <= j < len(layers) - 1)
    for _ in range(rounds):
        improved = False
        for i, ls in enumerate(layers):
            for k in range(len(ls) - 1):
                before = local(i)
                ls[k], ls[k + 1] = ls[k + 1], ls[k]
                if local(i) < before:
                    improved = True
                else:
                    ls[k], ls[k + 1] = ls[k + 1], ls[k]
        if not improved:
            return


def _graph(layer, chains):
    """The layers' nodes (boxes, then dummies), each node's layer, its
    neighbours, and the edges between each layer and the next (upper end
    first), by the upper layer's index."""
    nodes = {v for c in chains for v in c} | set(layer)
    of = {v: layer[v] if v in layer else v[2] for v in nodes}
    layers = [[] for _ in range(max(of.values(), default=0) + 1)]
    for v in list(layer) + [v for c in chains for v in c[1:-1]]:
        layers[of[v]].append(v)
    neighbours = {v: [] for v in nodes}
    edges = [[] for _ in layers]
    for c in chains:
        for u, v in zip(c, c[1:]):
            neighbours[u].append(v)
            neighbours[v].append(u)
            if of[u] != of[v]:
                edges[min(of[u], of[v])].append((u, v) if of[u] < of[v] else (v, u))
    return layers, neighbours, edges


def _order(layer, chains):
    """The boxes and dummies of each layer, ordered for few crossings."""
    layers, neighbours, edges = _graph(layer, chains)
    def total(ls):
        return sum(_crossings(ls[i], ls[i + 1], edges[i]) for i in range(len(ls) - 1))
    best, best_n = [list(x) for x in layers], total(layers)
    for s in range(SWEEPS):
        _sweep(layers, neighbours, down=s % 2 == 0)
        n = total(layers)
        if n < best_n:
            best, best_n = [list(x) for x in layers], n
    if best_n:
        _transpose(best, edges)
    return best, neighbours


# ------------------------------------------------------------ ports
_LEFT_NAMES = ("_a", "1", "_in", "_p")
_RIGHT_NAMES = ("_b", "2", "_out", "_n")


def _default_side(box, port):
    """The side of a port no line decides: inputs and ``*_a`` left,
    outputs and ``*_b`` right, else the side with fewer ports."""
    if port.signal is not None:
        return "left" if (port.signal == "input") != box.external else "right"
    if port.name.endswith(_LEFT_NAMES):
        return "left"
    if port.name.endswith(_RIGHT_NAMES):
        return "right"
    n_left = sum(p.side == "left" for p in box.ports.values())
    return "left" if 2 * n_left < len(box.ports) - 1 else "right"


def _set_sides(st, layer):
    """Each port on the side its lines leave to (the majority), else by
    :func:`_default_side`."""
    votes = {}
    for ln in st.lines:
        for box, port, other in ((ln.box_a, ln.port_a, ln.box_b), (ln.box_b, ln.port_b, ln.box_a)):
            step = layer[other] - layer[box]
            votes.setdefault((box, port), []).append(1 if step > 0 else -1 if step < 0 else 0)
    for box in st.boxes:
        for port in box.ports.values():
            port.side = "right"
        for port in box.ports.values():
            mine = votes.get((box.path, port.name), [])
            v = sum(mine)
            port.side = "right" if v > 0 else "left" if v < 0 else _default_side(box, port)
            port.mirror = 1 in mine and -1 in mine
    for ln in st.lines:                 # a loop on one box: both ends on one side if free to
        if ln.box_a == ln.box_b:
            ports = st.box(ln.box_a).ports
            a, b = ports[ln.port_a], ports[ln.port_b]
            if not any(votes.get((ln.box_a, ln.port_a), [])):
                a.side = b.side
            elif not any(votes.get((ln.box_b, ln.port_b), [])):
                b.side = a.side


# ------------------------------------------------------------ 4. positions
def _pava(desired, gaps):
    """Positions y_0 <= ... with y_{i+1} >= y_i + gaps[i] closest to
    ``desired`` in least squares (pool adjacent violators on the shifted
    problem)."""
    offset = [0.0]
    for g in gaps:
        offset.append(offset[-1] + g)
    blocks = []                              # [mean, weight]
    for d, o in zip(desired, offset):
        blocks.append([d - o, 1])
        while len(blocks) > 1 and blocks[-2][0] > blocks[-1][0]:
            m2, w2 = blocks.pop()
            m1, w1 = blocks.pop()
            blocks.append([(m1 * w1 + m2 * w2) / (w1 + w2), w1 + w2])
    z = [m for m, w in blocks for _ in range(w)]
    return [zi + o for zi, o in zip(z, offset)]


def _heights(layers, sizes):
    return {v: sizes[v][1] if v in sizes else 0.0 for ls in layers for v in ls}


def _place_y(layers, neighbours, sizes):
    """Centre heights: stacked, then pulled towards the neighbours' mean."""
    h = _heights(layers, sizes)
    def gap(u, v):
        return (h[u] + h[v]) / 2 + (BOX_GAP if u in sizes and v in sizes else DUMMY_GAP)
    y = {}
    for ls in layers:
        pos = 0.0
        for k, v in enumerate(ls):
            pos += gap(ls[k - 1], v) if k else h[v] / 2
            y[v] = pos
    for s in range(8):
        order = layers if s % 2 == 0 else layers[::-1]
        for ls in order:
            desired = [sum(y[u] for u in neighbours[v]) / len(neighbours[v])
                       if neighbours[v] else y[v] for v in ls]
            for v, yv in zip(ls, _pava(desired, [gap(a, b) for a, b in zip(ls, ls[1:])])):
                y[v] = yv
    top = min((y[v] - h[v] / 2 for ls in layers for v in ls), default=0.0)
    return {v: yv - top + MARGIN + 30 for v, yv in y.items()}


def _place_x(layers, sizes):
    """Left edge and width of each column."""
    cols, x = [], MARGIN + 40.0
    for ls in layers:
        w = max([sizes[v][0] for v in ls if v in sizes] or [20.0])
        cols.append((x, w))
        x += w + LAYER_GAP
    return cols


def _port_positions(st, boxes, neighbour_y):
    """(x, y, side) of every port: the ports of a side spread evenly,
    ordered by the height of what they connect to."""
    ports = {}
    for box in st.boxes:
        x, y, w, h = boxes[box.path]
        for side in ("left", "right"):
            mine = [p for p in box.ports.values() if p.side == side or p.mirror]
            mine.sort(key=lambda p: neighbour_y.get((box.path, p.name), y + h))
            top = y + (HEAD / 2 if len(mine) > 1 else 0)
            step = (h - (top - y)) / (len(mine) + 1)
            for k, p in enumerate(mine):
                key = (box.path, p.name) if p.side == side else (box.path, p.name, "mirror")
                ports[key] = (x if side == "left" else x + w,
                                             top + step * (k + 1), side)
    return ports


def _detour(port, box, toward):
    """Points that lead a line from ``port`` (x, y, side) of ``box`` round
    the box when what it goes to (``toward``) lies behind the port's side;
    none when the way is open."""
    x, y, side = port
    s = 1 if side == "right" else -1
    if (toward[0] - x) * s >= 0:
        return []
    bx, by, bw, bh = box
    edge = by + bh + 12 if toward[1] >= by + bh / 2 else by - 12
    back = bx - 16 if side == "right" else bx + bw + 16
    return [(x + 16 * s, y), (x + 16 * s, edge), (back, edge)]


def _end(ports, box, port, toward):
    """The place a line to ``toward`` (an x) leaves ``port`` of ``box``: its
    side, or its mirror on the other side when it lies that way."""
    main = ports[(box, port)]
    mirror = ports.get((box, port, "mirror"))
    if mirror and (toward - main[0]) * (1 if main[2] == "right" else -1) < 0:
        return mirror
    return main


def end_points(ports, boxes, line):
    """(x, y, side) of the two ends of ``line``."""
    if line.box_a == line.box_b:
        return ports[(line.box_a, line.port_a)], ports[(line.box_b, line.port_b)]
    ca = boxes[line.box_a][0] + boxes[line.box_a][2] / 2
    cb = boxes[line.box_b][0] + boxes[line.box_b][2] / 2
    return _end(ports, line.box_a, line.port_a, cb), _end(ports, line.box_b, line.port_b, ca)


def _loop(pa, pb, box):
    """A line between two ports of one box: out and back beside it, or
    round it (below) when the ports are on opposite sides."""
    if pa[2] == pb[2]:
        s = 1 if pa[2] == "right" else -1
        x = pa[0] + 18 * s
        return [pa[:2], (x, pa[1]), (x, pb[1]), pb[:2]]
    bx, by, bw, bh = box
    edge = by + bh + 12
    xa = pa[0] + (16 if pa[2] == "right" else -16)
    xb = pb[0] + (16 if pb[2] == "right" else -16)
    return [pa[:2], (xa, pa[1]), (xa, edge), (xb, edge), (xb, pb[1]), pb[:2]]


def _route(chain, ports, line, y, cols, of, boxes):
    """The points of a line: its two ports, a way round a box where a port
    faces away from the line, and, per layer it passes, the column's left
    and right edge at its dummy's height."""
    pa, pb = end_points(ports, boxes, line)
    if line.box_a == line.box_b:
        return _loop(pa, pb, boxes[line.box_a])
    mid = []
    for d in chain[1:-1]:
        x0, w = cols[of[d]]
        mid += [(x0, y[d]), (x0 + w, y[d])] if of[chain[0]] < of[chain[-1]] else \
            [(x0 + w, y[d]), (x0, y[d])]
    first = _detour(pa, boxes[line.box_a], (mid or [pb])[0])
    last = _detour(pb, boxes[line.box_b], (mid or [pa])[-1])[::-1]
    return [pa[:2]] + first + mid + last + [pb[:2]]


def _neighbour_heights(st, chains, y):
    """The height each port's line leaves towards (its first point past
    the port), to order the ports of a side."""
    ny = {}
    for ln, c in zip(st.lines, chains):
        ny[(ln.box_a, ln.port_a)] = y[c[1]] if len(c) > 1 else y[c[0]]
        ny[(ln.box_b, ln.port_b)] = y[c[-2]] if len(c) > 1 else y[c[-1]]
    return ny


def _extent(boxes, routes):
    width = max([x + w for x, _, w, _ in boxes.values()] + [300.0]) + MARGIN + 60
    height = max([yy + h for _, yy, _, h in boxes.values()] +
                 [yy for r in routes for _, yy in r] + [100.0]) + MARGIN
    return width, height


def layout(st):
    """The :class:`Layout` of a :class:`~acausal2d.visual.diagram.Structure`."""
    layer = _layers(_directed(st))
    chains = _chains(st, layer)
    layers, neighbours = _order(layer, chains)
    _set_sides(st, layer)
    sizes = {b.path: box_size(b) for b in st.boxes}
    y = _place_y(layers, neighbours, sizes)
    cols = _place_x(layers, sizes)
    of = {v: k for k, ls in enumerate(layers) for v in ls}
    boxes = {}
    for p, (w, h) in sizes.items():
        x0, cw = cols[of[p]]
        boxes[p] = (x0 + (cw - w) / 2, y[p] - h / 2, w, h)
    ports = _port_positions(st, boxes, _neighbour_heights(st, chains, y))
    routes = [_route(c, ports, ln, y, cols, of, boxes) for ln, c in zip(st.lines, chains)]
    width, height = _extent(boxes, routes)
    return Layout(boxes, ports, routes, width, height,
                  [[v for v in ls if v in sizes] for ls in layers])

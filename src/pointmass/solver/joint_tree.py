"""Which joints the direct solve takes (``joint_direct``), and the order it eliminates them in.

The bodies and the joints are the nodes of one graph, a body joined to each joint that acts
on it (Baraff 1996, "Linear-time dynamics using Lagrange multipliers"). Where that graph is a
forest, the saddle-point system of the joints' point blocks,

    [ M  Jᵀ ] [ Δv ]   [ 0 ]
    [ J  0  ] [ −P ] = [ r ],

factors without fill-in when every node is eliminated after its children, so one exact solve
costs O(nodes). Immovable bodies (and the world) are not nodes: a joint to one is a joint
with a single body. A node's pivot must be invertible: a joint node's own block is 0, so a
joint must have a body below it — a tree holds at most one joint to the world (or to an
immovable body), which becomes its root. What does not fit (a joint that closes a loop, a
second anchor of a rope bridge) is solved through the tree (``joint_loops``); sleeping
joints (``mode`` OFF) are not solved at all. ITERATIVE (Gauss–Seidel, one joint at a time)
is what is left when the tree cannot be factored.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..rigid.islands import find_root

#: Per joint, how the solver treats its point block.
OFF = 0  # both bodies asleep (or immovable): no row at all
ITERATIVE = 1  # Gauss–Seidel, one joint at a time (``joint_stages.solve_pass``)
DIRECT = 2  # the exact tree solve (``joint_direct``)
LOOP = 3  # closes a loop of a tree: solved through it (``joint_loops``)


@njit(cache=True, nogil=True)
def _ends(ja, jb, movable, j):
    """The joint's movable bodies (−1 for an end that is the world or immovable)."""
    a = ja[j] if movable[ja[j]] else -1
    b = jb[j] if jb[j] >= 0 and movable[jb[j]] else -1
    if a < 0:
        a, b = b, -1
    return a, b


@njit(cache=True, nogil=True)
def choose(ja, jb, awake, movable, mode):
    """Fill ``mode`` (J,) with OFF, DIRECT or LOOP (module docstring), in joint order: a
    joint that closes a loop, or a tree's second anchor, is LOOP (``joint_loops``)."""
    n = movable.shape[0]
    uf = np.arange(n)
    anchored = np.full(n, -1, np.int64)
    for j in range(ja.shape[0]):
        a, b = _ends(ja, jb, movable, j)
        if a < 0 or not (awake[a] or (b >= 0 and awake[b])):
            mode[j] = OFF
            continue
        mode[j] = LOOP
        if b >= 0:
            ra, rb = find_root(uf, a), find_root(uf, b)
            if ra == rb or (anchored[ra] >= 0 and anchored[rb] >= 0):
                continue
            uf[max(ra, rb)] = min(ra, rb)
            anchored[min(ra, rb)] = max(anchored[ra], anchored[rb])
        else:
            ra = find_root(uf, a)
            if anchored[ra] >= 0:
                continue
            anchored[ra] = j
        mode[j] = DIRECT


@njit(cache=True, nogil=True)
def order(ja, jb, movable, mode, nodes, parent):
    """Postorder of the DIRECT forest into ``nodes`` (node id: a body i as i, joint j as
    N + j) with each node's ``parent`` position in that order (−1 for a root); returns the
    node count P. A tree with a joint to the world is rooted at it, else at its lowest body."""
    n = movable.shape[0]
    jn = ja.shape[0]
    degree = np.zeros(n + 1, np.int64)
    for j in range(jn):
        if mode[j] == DIRECT:
            a, b = _ends(ja, jb, movable, j)
            degree[a + 1] += 1
            if b >= 0:
                degree[b + 1] += 1
    start = np.cumsum(degree)
    fill = start[:-1].copy()
    adjacent = np.empty(start[-1], np.int64)
    roots = np.full(n, -1, np.int64)  # the anchor of each body's tree, if any
    for j in range(jn):
        if mode[j] == DIRECT:
            a, b = _ends(ja, jb, movable, j)
            adjacent[fill[a]] = j
            fill[a] += 1
            if b >= 0:
                adjacent[fill[b]] = j
                fill[b] += 1
            else:
                roots[a] = j
    seen = np.zeros(n + jn, np.bool_)
    position = np.full(n + jn, -1, np.int64)
    up = np.full(n + jn, -1, np.int64)  # parent node id
    stack = np.empty(n + jn, np.int64)
    count = 0
    for first in range(n):
        if seen[first] or start[first + 1] == start[first]:
            continue
        top = _anchor(first, roots, ja, jb, movable, adjacent, start, n)
        depth = 0
        stack[0] = top
        seen[top] = True
        while depth >= 0:
            node = stack[depth]
            pushed = False
            for other in _neighbours(node, ja, jb, movable, adjacent, start, n):
                if not seen[other]:
                    seen[other] = True
                    up[other] = node
                    depth += 1
                    stack[depth] = other
                    pushed = True
                    break
            if not pushed:
                nodes[count] = node
                position[node] = count
                count += 1
                depth -= 1
    for p in range(count):
        parent[p] = position[up[nodes[p]]] if up[nodes[p]] >= 0 else -1
    return count


@njit(cache=True, nogil=True)
def _anchor(first, roots, ja, jb, movable, adjacent, start, n):
    """Root of the tree holding body ``first``: its anchor joint's node, else ``first``."""
    # walk the tree once to find an anchored body (trees are small next to the step)
    seen = {first: True}
    todo = [first]
    while todo:
        i = todo.pop()
        if roots[i] >= 0:
            return n + roots[i]
        for k in range(start[i], start[i + 1]):
            a, b = _ends(ja, jb, movable, adjacent[k])
            for other in (a, b):
                if other >= 0 and other not in seen:
                    seen[other] = True
                    todo.append(other)
    return first


@njit(cache=True, nogil=True)
def _neighbours(node, ja, jb, movable, adjacent, start, n):
    """Node ids next to ``node``: a body's joints, a joint's bodies."""
    out = []
    if node < n:
        for k in range(start[node], start[node + 1]):
            out.append(n + adjacent[k])
    else:
        a, b = _ends(ja, jb, movable, node - n)
        out.append(a)
        if b >= 0:
            out.append(b)
    return out


@njit(cache=True, nogil=True)
def unpair(ja, jb, movable, mode):
    """Send back to Gauss–Seidel (ITERATIVE) every LOOP joint that joins the same two bodies
    (or a body and the world) as a DIRECT joint does: two point blocks on one pair of bodies
    are redundant by structure (the second point cannot move along the line to the first
    through the tree: its mass through the tree, ``joint_loops``, is singular there, and
    near singular while either joint is open), so such a pair is held by soft rows."""
    for k in range(ja.shape[0]):
        if mode[k] != LOOP:
            continue
        c, d = _ends(ja, jb, movable, k)
        for j in range(ja.shape[0]):
            if mode[j] == DIRECT:
                a, b = _ends(ja, jb, movable, j)
                if (c == a and d == b) or (c == b and d == a):
                    mode[k] = ITERATIVE
                    break

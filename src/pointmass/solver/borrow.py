"""Borrowed array views for compiled kernels: arrays that count no references.

numba keeps an array's memory alive by counting references to it, with an atomic increment and
decrement (``NRT_incref`` / ``NRT_decref``: a locked instruction each). A compiled function
counts each array argument once on entry and once on exit, and numba's pruning of such pairs
does not reach across a call that LLVM did not inline. So a kernel that calls others in a loop
pays two locked instructions per array argument per call: the soft step of a world of one
resting sphere (``body_soft.contact_step``: 4 substeps, ~20 kernels each, 15–30 arrays per
call) made ~3 000 of them a step, a third of its time (perf: the samples land on
``lock incq`` / ``lock decq``).

A borrowed view is the same array with a null owner record: numba's counting skips a null
owner with one test, so whatever a borrowed view is passed to counts nothing. It is safe
while the owner lives: an argument from Python lives for the call; an array made inside the
kernel must be kept alive to the end of the views' use (``keep_alive``). A borrowed view must never
be returned to Python (it would point at memory nobody owns) nor stored beyond the call.
"""

from __future__ import annotations

import numpy as np
from numba import njit, types
from numba.core import cgutils
from numba.extending import intrinsic


@intrinsic
def borrowed(typingctx, array):
    """``array`` as a borrowed view (module docstring): its owner record and parent object are
    null, its data, shape and strides those of ``array``."""
    if not isinstance(array, types.Array):
        return None

    def codegen(context, builder, signature, args):
        view = context.make_array(array)(context, builder, value=args[0])
        view.meminfo = cgutils.get_null_value(view.meminfo.type)
        view.parent = cgutils.get_null_value(view.parent.type)
        return view._getvalue()

    return array(array), codegen


@njit(cache=True, nogil=True)
def keep_alive(*owners):
    """Nothing: a use of ``owners`` that keeps them (and so their borrowed views) alive up to
    this point of the caller."""
    return len(owners)


@njit(cache=True, inline="always")
def scratch(shape, dtype):
    """A new array of ``shape`` and ``dtype`` (uninitialised, as ``np.empty``) and a borrowed
    view of it: (owner, view). Keep the owner alive while the view is used (``keep_alive``)."""
    owner = np.empty(shape, dtype)
    return owner, borrowed(owner)


@njit(cache=True, inline="always")
def zeroed(shape, dtype):
    """``scratch`` filled with zeros (``np.zeros``)."""
    owner = np.zeros(shape, dtype)
    return owner, borrowed(owner)

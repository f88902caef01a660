"""Row storage shared by the particle and body stores: arrays with spare capacity, read through
views of their first ``count`` rows that are made once per change of count or capacity (a
step reads them as attributes, not slices: six slices were a tenth of a 1-particle world's
step, 54 were 28 % of a sleeping 10-box tower's)."""

from __future__ import annotations

from operator import attrgetter
from typing import Any


class RowViews:
    """Mixin: ``_refresh_views`` makes ``_view_NAME = _NAME[:_count]`` for each name in the
    class's ``_VIEW_FIELDS``; ``view`` makes the property that returns one. Deep copies and
    pickles rebuild the views instead of copying them (a copy would make them arrays of their
    own, no longer views of the storage)."""

    _VIEW_FIELDS: tuple[str, ...] = ()
    _count: int

    def _refresh_views(self) -> None:
        n = self._count
        for name in self._VIEW_FIELDS:
            setattr(self, "_view_" + name, getattr(self, "_" + name)[:n])

    def __getstate__(self) -> dict:
        return {k: v for k, v in self.__dict__.items() if not k.startswith("_view_")}

    def __setstate__(self, state: dict) -> None:
        self.__dict__.update(state)
        self._refresh_views()


def view(name: str, doc: str) -> Any:
    """The property returning the view of field ``name`` (see ``RowViews``). Typed ``Any`` so
    that a type checker reads the attribute as the array it returns, not as a property."""
    return property(attrgetter("_view_" + name), doc=doc)

"""Keyword arguments as the options table's settings.

Every keyword is a key of the options table (``octrace.options()``, the table the CLI's flags,
its ``--help`` and the studio's sessions come from); its value is turned into the text the CLI
would take (a tuple of numbers joined by the separator the table's argument shows, ``True`` for
a flag) and handed to the pipeline library, which parses and checks it with the same code as
the CLI. Nothing here knows a range, a default or a choice.
"""

from __future__ import annotations

import difflib
import logging
import numbers
import warnings

from . import _octrace

_LOG = logging.getLogger("octrace")


class OctraceWarning(UserWarning):
    """A setting that has no effect, or something octrace changed for you (the CLI's warnings)."""


_TABLE = {o["key"]: o for o in _octrace.options()}


def table():
    """The options table, one dict per setting (key, kind, default, range, choices, help, ...)."""
    return [dict(o) for o in _TABLE.values()]


def default(key):
    """The table's default of a numeric setting."""
    return _TABLE[key]["default_value"]


def default_text(key):
    """The table's default of a setting as its help says it (a text setting's default value)."""
    return _TABLE[key]["default"]


def _scalar(key, value):
    if isinstance(value, bool):
        raise _octrace.UsageError(f"'{key}': expected a value, got {value!r}")
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        return repr(float(value))
    if isinstance(value, str):
        return value
    raise _octrace.UsageError(f"'{key}': expected a number or text, got {type(value).__name__} {value!r}")


def _texts(option, value):
    """The settings texts of one keyword: [] when it is off, one text, or one per repeated value."""
    key, kind = option["key"], option["kind"]
    if value is None:
        return []
    if kind == "flag":
        if value is True:
            return [""]
        if value is False:
            return []
        raise _octrace.UsageError(f"'{key}': expected True or False, got {value!r}")
    if kind == "choice" and isinstance(value, bool) and set(option["choices"]) == {"on", "off"}:
        return ["on" if value else "off"]
    if isinstance(value, (list, tuple)) or type(value).__name__ == "ndarray":
        parts = list(value)
        separator = option["separator"]
        if parts and all(isinstance(p, str) for p in parts) and (separator is None or all(separator in p for p in parts)):
            return parts  # a repeatable setting, once per value (`cut`, `bake_light`)
        # Otherwise the parts of one value: numbers, or texts with a unit (colour_range=("5degC", "20degC")).
        if separator is None:
            raise _octrace.UsageError(f"'{key}': expected one value ({option['argument']}), got {value!r}")
        return [separator.join(_scalar(key, p) for p in parts)]
    return [_scalar(key, value)]


def _unknown(key, accepted, call):
    close = difflib.get_close_matches(key, sorted(accepted), n=3, cutoff=0.6)
    hint = f"; did you mean {', '.join(repr(c) for c in close)}?" if close else ""
    if key in _TABLE and not close:
        part = _TABLE[key]["part"]
        where = {"request": "octrace.open() (what to read)", "surface": "octrace.surface() (the build; it also sets the "
                 "threads and memory of the surface's renders)" if key in ("threads", "max_memory") else "octrace.surface() (the build)",
                 "render": "Surface.render()", "figure": "Surface.render(figure=True, ...)"}.get(part, "another call")
        hint = f" ({key!r} is a setting of {where}; see octrace.options())"
    return TypeError(f"{call}() got an unexpected keyword argument {key!r}{hint}")


def keys(parts, shading=False):
    """The keys of the settings of ``parts`` ("request", "surface", "render", "figure"); with
    ``shading`` also the surface's settings that only shading reads (colours, lighting)."""
    return {k for k, o in _TABLE.items() if o["part"] in parts or (shading and o["shading"])}


def slice_keys(request=True):
    """The settings of a slice (those ``octrace slice`` takes: plane, at, index, size, window,
    colour map, figure, ...); with ``request`` also what to read (var, region, time, ...)."""
    return {k for k, o in _TABLE.items() if o["slice"] and (request or o["part"] != "request")}


def reader_keys():
    """The settings that choose what to read from an input (those `octrace info` takes)."""
    return {k for k, o in _TABLE.items() if o["part"] and "info" in o["commands"].split()}


def settings(kwargs, accepted, call):
    """The (key, text) pairs of ``kwargs``, each a key of ``accepted``: an unknown keyword
    raises TypeError naming the nearest valid ones."""
    out = []
    for key, value in kwargs.items():
        if key not in accepted:
            raise _unknown(key, accepted, call)
        out.extend((key, text) for text in _texts(_TABLE[key], value))
    return out


def flush_log():
    """Hands the pipeline's messages to Python: warnings as OctraceWarning, the rest to the
    logger "octrace"."""
    for level, text in _octrace.take_log():
        if level >= 3:
            _LOG.error(text)
        elif level == 2:
            warnings.warn(text, OctraceWarning, stacklevel=3)
        elif level == 1:
            _LOG.info(text)
        else:
            _LOG.debug(text)


def warn_unused(keys, renderer):
    """Warns of the settings that ``renderer`` does not read, as the CLI does."""
    for text in _octrace.unused_settings(list(keys), renderer):
        warnings.warn(text, OctraceWarning, stacklevel=3)

"""The xarray accessor: ``da.octrace.render(iso=10, ...)``, ``da.octrace.surface(...)``,
``da.octrace.slice(plane="z", at=500)``, ``da.octrace.volume()``, ``da.octrace.describe()``.

The DataArray's values, coordinates and attributes go as they are to the C++ CF interpretation
of the NetCDF reader (io/CfDataset.h): the same axis roles, geographic mapping, masking, uneven
depth and ``positive`` rules as ``octrace render FILE --var ...``, so the same settings give the
same pixels. Nothing is interpreted here: this module only lists the arrays. Times are handed
over as the numbers a file stores (xarray's decoded datetimes and cftime dates are encoded back
with the coordinate's own units and calendar); choose a time step with xarray's ``.sel`` /
``.isel`` first, or with ``time=`` as on the CLI. Dask-backed arrays are computed here.
A parametric vertical coordinate (ROMS's s_rho, CF formula_terms) needs its terms, which a
DataArray carries only as coordinates: open the file with ``decode_coords="all"``.
"""

from __future__ import annotations

import numpy as np

from . import _octrace, _settings

_INTS = (np.int8, np.uint8, np.int16, np.uint16, np.int32, np.uint32, np.int64, np.uint64)


def _attribute(value):
    if isinstance(value, (str, bytes)):
        return value.decode() if isinstance(value, bytes) else value
    array = np.atleast_1d(np.asarray(value))
    if array.dtype.kind in "biuf":
        return [float(v) for v in array.astype(np.float64)]
    return str(value)


def _values(name, variable):
    """The variable's values as C-contiguous numbers (times encoded as the file would store
    them) and the attributes that say how (units, calendar), or None."""
    data = variable.values  # computes a Dask-backed array
    extra = {}
    if np.issubdtype(data.dtype, np.datetime64) or (data.dtype == object and data.size and hasattr(data.flat[0], "calendar")):
        from xarray.coding.times import encode_cf_datetime

        units = variable.encoding.get("units")
        calendar = variable.encoding.get("calendar")
        numbers, units, calendar = encode_cf_datetime(data, units=units, calendar=calendar)
        data = np.asarray(numbers, dtype=np.float64)
        extra = {"units": units, "calendar": calendar}
    elif np.issubdtype(data.dtype, np.timedelta64) or data.dtype == object or data.dtype.kind in "SUc":
        return None, extra
    elif data.dtype == np.bool_:
        data = data.astype(np.uint8)
    elif data.dtype not in (np.float32, np.float64) and data.dtype.type not in _INTS:
        data = data.astype(np.float64)
    return np.ascontiguousarray(data), extra


def _variable(name, variable):
    values, extra = _values(name, variable)
    attributes = {str(k): _attribute(v) for k, v in variable.attrs.items()}
    # xarray's decode_coords="all" moves formula_terms to the encoding (and its terms into the
    # coordinates): the reader needs it where a file has it.
    if "formula_terms" in variable.encoding and "formula_terms" not in attributes:
        attributes["formula_terms"] = str(variable.encoding["formula_terms"])
    attributes.update(extra)
    return {"name": str(name), "dims": [str(d) for d in variable.dims], "shape": [int(n) for n in variable.shape],
            "values": values, "attributes": attributes}


def cf_variables(da):
    """The DataArray and its coordinates as the variables of a NetCDF file would list them."""
    name = da.name if da.name is not None else "data"
    variables = [_variable(name, da.variable)]
    for cname, coord in da.coords.items():
        # 0-D numbers go too: a parametric vertical coordinate's constants (ROMS's hc)
        if (coord.ndim == 0 and coord.dtype.kind not in "biuf") or cname == name:
            continue
        variables.append(_variable(cname, coord.variable))
    return variables


def _description(da):
    return f"xarray DataArray {da.name if da.name is not None else 'data'}"


def _reader_settings(kwargs, call):
    accepted = _settings.reader_keys() - {"var", "series", "volume"}
    return _settings.settings(kwargs, accepted, call)


def _split(kwargs):
    """Reader settings (region, depth_range, time, vertical_scale, max_memory) and the rest."""
    reader = _settings.reader_keys() - {"var", "series", "volume"}
    return {k: v for k, v in kwargs.items() if k in reader}, {k: v for k, v in kwargs.items() if k not in reader}


def register():
    """Registers ``DataArray.octrace`` (done on ``import octrace`` when xarray is installed)."""
    import xarray as xr

    from . import Volume, slice, surface  # noqa: A004 - octrace.slice

    @xr.register_dataarray_accessor("octrace")
    class OctraceAccessor:
        """octrace on this DataArray: ``da.octrace.render(iso=10, depth=9, size=(800, 600))``."""

        def __init__(self, da):
            self._da = da

        def volume(self, **reader_options):
            """The field octrace reads from the DataArray (region, depth_range, time,
            vertical_scale, max_memory as on the CLI), as an ``octrace.Volume``."""
            return self._read(reader_options, "volume", planar=False)

        def _read(self, reader_options, call, planar):
            settings = _reader_settings(reader_options, call)
            variables = cf_variables(self._da)
            try:
                return Volume._wrap(_octrace.read_cf(variables, _description(self._da), settings, planar))
            finally:
                _settings.flush_log()

        def describe(self, **reader_options):
            """What ``octrace info`` says of a file holding this DataArray."""
            settings = _reader_settings(reader_options, "describe")
            try:
                return _octrace.describe_cf(cf_variables(self._da), _description(self._da), settings)
            finally:
                _settings.flush_log()

        def surface(self, *, progress=None, **options):
            """The isosurface's octree (``octrace.surface``), the reader's settings included."""
            reader, rest = _split(options)
            return surface(self.volume(**reader), progress=progress, **rest)

        def render(self, *, size=None, camera=None, renderer=None, figure=False, **options):
            """One frame: the surface's settings (iso, depth, colormap, ...) and render()'s
            (size, camera, renderer, figure, background, ...) together."""
            render_keys = _settings.keys(("render", "figure"), shading=True)
            view = {k: v for k, v in options.items() if k in render_keys}
            build = {k: v for k, v in options.items() if k not in render_keys}
            shell = self.surface(**build)
            return shell.render(size=size, camera=camera, renderer=renderer, figure=figure, **view)

        def slice(self, plane=None, at=None, index=None, size=None, figure=False, **options):
            """A planar slice (``octrace.slice``) of the field ``volume()`` reads, the reader's
            settings (region, depth_range, time, ...) included: ``octrace slice``'s pixels. A 2-D
            DataArray (an SST map, bathymetry; or one vertical level) is drawn as a map."""
            reader, rest = _split(options)
            field = self._read(reader, "slice", planar=True)
            return slice(field, plane=plane, at=at, index=index, size=size, figure=figure, **rest)

    return OctraceAccessor

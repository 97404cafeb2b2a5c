"""octrace for Python: isosurfaces of ocean, medical and city data as voxel octrees, drawn by
exact octree ray casters on the CPU (no GL, no display).

    import octrace
    temp = octrace.open("levitus_climatology.cdf", var="TEMP", region=(120, 180, 10, 60))
    shell = octrace.surface(temp, iso=10, depth=9, colormap="viridis")
    img = shell.render(size=(800, 600))
    img.save("temp10.png")          # the CLI's PNG, byte for byte
    pixels = np.asarray(img)        # (600, 800, 4) uint8, no copy
    top = temp.slice(plane="z", at=0, figure=True)  # octrace slice: a map at the surface

Keyword arguments are the keys of the options table (``octrace.options()``), the table the
CLI's flags come from: ``--colour-range 0,20`` is ``colour_range=(0, 20)``, ``--size 800x600``
is ``size=(800, 600)``, a flag is ``True``. Values are checked by the same code as the CLI's;
errors are ``octrace.UsageError`` (a ValueError) and its siblings, messages name the keyword.
"""

from __future__ import annotations

import builtins
import os
import tempfile
import warnings

from . import _octrace, _settings
from ._octrace import FileError, InputError, LimitError, OutputError, UsageError
from ._settings import OctraceWarning

__all__ = [
    "open", "load", "surface", "slice", "view", "animate", "options", "describe", "renderers",
    "Volume", "Input", "Surface", "Image",
    "UsageError", "InputError", "FileError", "LimitError", "OutputError", "OctraceWarning",
]


def options():
    """The options table: one dict per setting, with its key (the keyword), kind, default,
    range or choices, unit, help and the CLI flag it is."""
    return _settings.table()


def renderers():
    """The renderers' names (``renderer=``), the paper renderers and their aliases included."""
    return list(_octrace.renderer_names())


def describe(path, **reader_options):
    """What ``octrace info PATH`` prints: the format, dimensions, variables, geometry."""
    settings = _settings.settings(reader_options, _settings.reader_keys(), "describe")
    try:
        return _octrace.describe(os.fspath(path), settings)
    finally:
        _settings.flush_log()


class Volume:
    """A 3-D field: samples on a grid, read from a file (``octrace.open``) or given as a NumPy
    array.

    ``Volume(values, spacing=(sx, sy, sz), origin=(ox, oy, oz), direction=None, name="",
    units="")``: ``values`` has axes (z, y, x), as SimpleITK's ``GetArrayFromImage`` and
    NetCDF's (depth, lat, lon) give them; ``spacing`` and ``origin`` are in x, y, z order;
    ``direction`` is a 3x3 matrix whose columns are the grid axes in world space. NaN samples
    are masked. A C-contiguous float32 array without NaN is read in place, without a copy:
    the Volume and the surfaces built from it keep the array alive and read it, so change it
    only when no build runs (a built surface's octree does not change). Other arrays are
    converted to one (an OctraceWarning says so), and an array with NaN is copied to mask them.
    """

    def __init__(self, values, spacing=(1.0, 1.0, 1.0), origin=(0.0, 0.0, 0.0), direction=None, name="array", units="",
                 patient_lps=False):
        import numpy as np

        array = np.asarray(values)
        if array.ndim != 3:
            raise UsageError(f"a volume needs a 3-D array with axes (z, y, x), got {array.ndim} dimension(s) {array.shape}")
        if array.size == 0:
            raise UsageError(f"the array is empty: shape {array.shape}")
        if not (np.issubdtype(array.dtype, np.number) or array.dtype == np.bool_) or np.iscomplexobj(array):
            raise UsageError(f"the array's samples must be real numbers, got dtype {array.dtype}")
        if type(values).__name__ == "DataArray" and hasattr(values, "octrace"):
            warnings.warn("Volume() takes the DataArray's values alone (unit spacing, no coordinates); "
                          "da.octrace.volume() reads its coordinates and attributes as the NetCDF reader does",
                          OctraceWarning, stacklevel=2)
        self._converted = array.dtype != np.float32 or not array.flags.c_contiguous
        if self._converted:
            why = f"dtype {array.dtype}" if array.dtype != np.float32 else "a non-contiguous layout"
            warnings.warn(f"the array ({why}) is converted to C-contiguous float32", OctraceWarning, stacklevel=2)
            array = np.ascontiguousarray(array, dtype=np.float32)
        spacing = _triple("spacing", spacing)
        origin = _triple("origin", origin)
        if any(not np.isfinite(s) or s <= 0 for s in spacing):
            raise UsageError(f"'spacing' must be finite and positive, got {spacing}")
        if any(not np.isfinite(o) for o in origin):
            raise UsageError(f"'origin' must be finite, got {origin}")
        matrix = np.eye(3) if direction is None else np.asarray(direction, dtype=np.float64)
        if matrix.shape != (3, 3):
            raise UsageError(f"'direction' must be a 3x3 matrix, got shape {matrix.shape}")
        self._field = _octrace.array_field(array, origin, spacing, [float(v) for v in matrix.reshape(-1)], str(name),
                                           str(units), bool(patient_lps))
        _settings.flush_log()

    @classmethod
    def _wrap(cls, field):
        v = cls.__new__(cls)
        v._field = field
        v._converted = False
        return v

    shape = property(lambda self: self._field.shape, doc="Samples per axis, (z, y, x).")
    spacing = property(lambda self: self._field.spacing, doc="Sample spacing, (x, y, z) in world units.")
    origin = property(lambda self: self._field.origin, doc="World position of sample (0, 0, 0), (x, y, z).")
    direction = property(lambda self: _matrix(self._field.direction), doc="3x3: columns are the grid axes in world space.")
    coords = property(lambda self: self._field.coords, doc="Uneven axes' positions (x, y, z); empty where uniform.")
    name = property(lambda self: self._field.name)
    units = property(lambda self: self._field.units)
    notes = property(lambda self: list(self._field.notes), doc="How the grid was mapped (e.g. geographic).")
    bounds = property(lambda self: self._field.bounds, doc="World bounding box ((x0, y0, z0), (x1, y1, z1)).")
    valid_range = property(lambda self: self._field.valid_range, doc="(min, max) of the valid samples.")
    values = property(lambda self: self._field.values, doc="The samples, axes (z, y, x), read-only, without a copy.")
    in_place = property(lambda self: self._field.in_place and not self._converted,
                        doc="True when the samples are the NumPy array given, read in place (no copy).")
    mask = property(lambda self: self._field.mask, doc="1 where a sample is valid, axes (z, y, x); None when all are.")

    def surface(self, *, progress=None, **options):
        """The isosurface's octree (``octrace.surface(self, ...)``)."""
        return surface(self, progress=progress, **options)

    def slice(self, plane=None, at=None, index=None, size=None, figure=False, **options):
        """A planar slice through the samples as an ``Image`` (``octrace.slice(self, ...)``)."""
        return slice(self, plane=plane, at=at, index=index, size=size, figure=figure, **options)

    def __repr__(self):
        z, y, x = self.shape
        units = f" [{self.units}]" if self.units else ""
        return f"<octrace.Volume {self.name or 'array'}{units} {x}x{y}x{z}>"


class Input:
    """An input built straight into an octree (a city model, an octree file), with its reader
    settings; ``octrace.surface(input, ...)`` builds it."""

    def __init__(self, path, reader_settings):
        self.path = path
        self._settings = reader_settings

    def __repr__(self):
        return f"<octrace.Input {self.path}>"


def open(path, **reader_options):  # noqa: A001 - the package's reader, as xarray.open_dataset
    """Reads ``path`` with any reader of the CLI: NetCDF, Zarr v2 stores (a folder), DICOM
    folders and files, NRRD, NIfTI, MetaImage, molecules, ``analytic:NAME``; city models and octree files become an ``Input``
    built by ``octrace.surface``. ``reader_options``: var, time, region, depth_range,
    vertical_scale, series, max_memory and the city settings (crs, lod_select, dem, ...)."""
    path = os.fspath(path)
    settings = _settings.settings(reader_options, _settings.reader_keys(), "open")
    try:
        if not _octrace.is_field_input(path):
            return Input(path, settings)
        return Volume._wrap(_octrace.read_field(path, settings))
    finally:
        _settings.flush_log()


def surface(source, *, progress=None, **options):
    """Builds the isosurface's shell octree once: ``source`` is a Volume, a NumPy array (axes
    z, y, x), an xarray DataArray (as ``da.octrace.surface``), an ``Input`` or a path.
    ``options``: iso, depth, colormap, colour_by, floor, window, cut, bake, ...
    (``octrace.options()``). ``progress(fraction)`` is called as the build goes; Ctrl-C
    (KeyboardInterrupt) cancels it."""
    if type(source).__name__ == "DataArray" and hasattr(source, "octrace"):
        return source.octrace.surface(progress=progress, **options)
    if type(source).__name__ == "Dataset":
        raise UsageError("a Dataset holds several variables: choose one, e.g. octrace.surface(ds['TEMP'], ...)")
    if type(source).__name__ == "ndarray":
        source = Volume(source)
    # A Volume is read already: what chooses the field (var, region, time, ...) has no place.
    accepted = _settings.keys(("surface",) if isinstance(source, Volume) else ("request", "surface"))
    settings = _settings.settings(options, accepted, "surface")
    try:
        if isinstance(source, Volume):
            shell = _octrace.build_shell(source._field, "", settings, progress)
        elif isinstance(source, Input):
            shell = _octrace.build_shell(None, source.path, source._settings + settings, progress)
        else:
            shell = _octrace.build_shell(None, os.fspath(source), settings, progress)
    finally:
        _settings.flush_log()
    return Surface(shell, settings)


def slice(source, plane=None, at=None, index=None, size=None, figure=False, **options):  # noqa: A001 - octrace slice
    """A planar slice through a field's samples, as ``octrace slice`` draws it, as an ``Image``
    (its ``stats`` are the CLI's ``--stats``). ``source``: a Volume, a NumPy array (axes z, y,
    x), an xarray DataArray or a path (then ``var``, ``region``, ``time``, ... choose what to
    read, as ``octrace.open`` takes them). ``plane``: axial, coronal, sagittal (patient volumes;
    the default for them) or x, y, z (the default otherwise); ``at``: where along the plane's
    normal (world units, mm for patient volumes; on a geographic grid the depth in metres for
    z, the longitude or latitude for x or y), or ``index``: the sample across the plane (by
    default the middle one); ``size=(W, H)``: the image, unset one pixel per sample;
    ``figure=True``: the CLI's figure (grey or colour bar, letters or ticks, title). Other
    ``options``: window, colormap, colour_range, masked_colour, background, title, dpi,
    print_size, scale_bar, coastline, threads (``octrace.options()``)."""
    if type(source).__name__ == "DataArray" and hasattr(source, "octrace"):
        return source.octrace.slice(plane=plane, at=at, index=index, size=size, figure=figure, **options)
    if type(source).__name__ == "ndarray":
        source = Volume(source)
    merged = {}
    for key, value in (("plane", plane), ("at", at), ("index", index), ("size", size), ("figure", figure or None)):
        if value is not None:
            merged[key] = value
    merged.update(options)
    # A Volume is read already: what chooses the field (var, region, time, ...) has no place.
    accepted = _settings.slice_keys(request=not isinstance(source, Volume))
    settings = _settings.settings(merged, accepted, "slice")
    try:
        if isinstance(source, Volume):
            frame = _octrace.slice_field(source._field, settings)
        elif isinstance(source, Input):
            frame = _octrace.slice_path(source.path, source._settings + settings)
        else:
            frame = _octrace.slice_path(os.fspath(source), settings)
    finally:
        _settings.flush_log()
    return Image(frame)


def load(path, **options):
    """An octree file (``.oct``: ``Surface.save``, ``octrace build``) as a Surface."""
    settings = _settings.settings(options, _settings.keys(("surface",), shading=True), "load")
    try:
        return Surface(_octrace.load_shell(os.fspath(path), settings), settings)
    finally:
        _settings.flush_log()


class Surface:
    """A built isosurface (a shell octree), rendered as often as wanted."""

    def __init__(self, shell, settings):
        self._shell = shell
        self._settings = settings

    iso = property(lambda self: self._shell.iso)
    depth = property(lambda self: self._shell.depth, doc="Octree depth: 2**depth voxels per cube edge.")
    boundary_voxels = property(lambda self: self._shell.boundary_voxels)
    bounds = property(lambda self: self._shell.bounds, doc="World box of the voxels ((x0, y0, z0), (x1, y1, z1)).")
    build_ms = property(lambda self: self._shell.build_ms)
    nbytes = property(lambda self: self._shell.bytes, doc="Bytes the octree takes in memory.")

    def render(self, *, size=None, camera=None, renderer=None, figure=False, **options):
        """One frame as an ``Image``. ``size=(W, H)``; ``camera``: a dict of camera_pos,
        look_at, up, fov, projection, ortho_height (or give them as keywords), unset: framing
        the surface; ``renderer``: a name of ``octrace.renderers()``; ``figure=True``: the CLI's
        figure (title, colour bar, axes); other ``options``: background, light, colours and
        colour map, lighting, the renderers' settings (``octrace.options()``). A setting the
        renderer does not read gives an OctraceWarning, as the CLI's warning."""
        merged = dict(camera or {})
        for key, value in (("size", size), ("renderer", renderer), ("figure", figure or None)):
            if value is not None:
                merged[key] = value
        overlap = set(merged) & set(options)
        if overlap:
            raise TypeError(f"render() got {sorted(overlap)[0]!r} twice")
        merged.update(options)
        view_keys = _settings.keys(("render", "figure"))
        given = _settings.settings(merged, view_keys | _settings.keys((), shading=True), "render")
        render_settings = [(k, t) for k, t in given if k in view_keys]
        surface_settings = [(k, t) for k, t in given if k not in view_keys]
        _settings.warn_unused([k for k, _ in given], dict(render_settings).get("renderer", _settings.default_text("renderer")))
        try:
            frame = _octrace.render(self._shell, surface_settings, render_settings)
        finally:
            _settings.flush_log()
        return Image(frame)

    def camera(self, *, size=None, orbit=None, dolly=None, **view):
        """The camera of a frame, as the dict of camera settings render(camera=...) takes
        (camera_pos, look_at, up, fov, projection): framing the surface unless ``view`` places
        it, then turned by ``orbit=(yaw, pitch)`` degrees about the look-at point and moved
        closer by ``dolly`` (a factor of the distance, < 1 comes closer) — the studio's moves."""
        view = dict(view)
        if size is not None:
            view["size"] = size
        settings = _settings.settings(view, _settings.keys(("render",)), "camera")
        cam = _octrace.move_camera(self._shell, settings, "", 0.0, 0.0, 1)
        if orbit is not None:
            yaw, pitch = orbit
            cam = _octrace.move_camera(self._shell, settings + _settings.settings(cam, _settings.keys(("render",)), "camera"),
                                       "orbit", float(yaw), float(pitch), 1)
        if dolly is not None:
            cam = _octrace.move_camera(self._shell, settings + _settings.settings(cam, _settings.keys(("render",)), "camera"),
                                       "dolly", float(dolly), 0.0, 1)
        return cam

    def save(self, path, compression=19):
        """Writes the octree as an octree file (``.oct``, as ``octrace build``); read it back
        with ``octrace.load``."""
        try:
            _octrace.save_shell(self._shell, os.fspath(path), int(compression))
        finally:
            _settings.flush_log()

    def __repr__(self):
        return (f"<octrace.Surface {self._shell.field_name or self._shell.input} iso={self.iso:g} "
                f"depth={self.depth} voxels={self.boundary_voxels}>")


class Image:
    """A rendered frame or slice. ``np.asarray(img)`` is its (H, W, 4) uint8 sRGB pixels without a copy
    (the bytes a PNG of it holds); ``img.depth`` the distance along each ray (float32, inf for a
    miss); ``img.stats`` the dict of the CLI's ``--stats``; in Jupyter it shows itself."""

    def __init__(self, frame):
        if not isinstance(frame, _octrace.Frame):
            raise TypeError("an octrace.Image comes from Surface.render() or octrace.slice(); "
                            f"got {type(frame).__name__} (an image of your own is np.asarray'd as it is)")
        self._frame = frame

    width = property(lambda self: self._frame.width)
    height = property(lambda self: self._frame.height)
    size = property(lambda self: (self._frame.width, self._frame.height), doc="(W, H), as ``size=`` takes it.")
    depth = property(lambda self: self._frame.depth, doc="Distance from the eye along each ray, (H, W) float32.")
    stats = property(lambda self: self._frame.stats, doc="The CLI's --stats keys (docs/user/cli.md).")
    dpi = property(lambda self: self._frame.dpi, doc="A figure's dots per inch (0: a plain image).")

    @property
    def rgba(self):
        """The (H, W, 4) uint8 sRGB pixels, read-only, sharing the frame's memory."""
        return self._frame.rgba

    def __array__(self, dtype=None, copy=None):
        array = self._frame.rgba
        if copy:
            array = array.copy()
        if dtype is not None and array.dtype != dtype:
            if copy is False:
                raise ValueError(f"an Image is uint8; a {dtype} array needs a copy")
            array = array.astype(dtype)
        return array

    def save(self, path):
        """Writes the image through octrace's writers (``.png``, ``.tif``, ``.exr`` with depth),
        atomically, as the CLI writes ``-o``."""
        try:
            self._frame.save(os.fspath(path))
        finally:
            _settings.flush_log()

    def _repr_png_(self):
        with tempfile.TemporaryDirectory(prefix="octrace-") as folder:
            path = os.path.join(folder, "frame.png")
            self._frame.save(path)
            with builtins.open(path, "rb") as f:
                return f.read()

    def __repr__(self):
        return f"<octrace.Image {self.width}x{self.height}>"


from ._animate import animate  # noqa: E402 - after the classes the two modules use
from ._view import view  # noqa: E402


def _register_xarray():
    """``DataArray.octrace`` (the accessor of octrace/_xarray.py), when xarray is installed."""
    try:
        import xarray  # noqa: F401
    except ImportError:
        return
    from ._xarray import register

    register()


_register_xarray()


def _triple(name, value):
    try:
        a, b, c = (float(v) for v in value)
    except (TypeError, ValueError):
        raise UsageError(f"'{name}': expected three numbers (x, y, z), got {value!r}") from None
    return (a, b, c)


def _matrix(flat):
    import numpy as np

    return np.asarray(flat, dtype=np.float64).reshape(3, 3)


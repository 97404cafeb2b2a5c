"""An interactive view in Jupyter without GL: octrace renders each frame on the CPU and
jupyter_rfb (a remote frame buffer) shows it. Drag to orbit, Shift+drag or the middle button to
pan, the wheel to zoom, as in the studio (the same camera moves: octrace/model/Navigation.h).
Given a Volume, an iso slider rebuilds the surface; given an xarray DataArray with a time (or
other) dimension, a second slider steps through it, the camera kept and the step's date shown."""

from __future__ import annotations

from . import _octrace, _settings


def _require_rfb():
    try:
        import jupyter_rfb
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError("octrace.view needs jupyter_rfb (pip install jupyter_rfb)") from e
    return jupyter_rfb


def view(source, *, size=(640, 480), iso=None, iso_range=None, dim=None, **options):
    """A widget showing ``source``: a Surface; a Volume whose surface the ``iso`` slider
    rebuilds over ``iso_range`` (default the volume's valid range); or an xarray DataArray
(the iso slider over its first step's valid range unless ``iso_range`` is given),
    read as ``da.octrace.volume()`` reads it, with a slider over ``dim`` (default ``"time"``
    when the DataArray has it; any dimension beyond the three of space) as well. ``options``
    are render()'s (renderer, background, colormap, ...) and surface()'s (depth, ...), and
    for a DataArray the reader's (region, depth_range, vertical_scale)."""
    rfb = _require_rfb()
    from . import Surface, Volume

    class SurfaceView(rfb.RemoteFrameBuffer):
        """The frame buffer: renders with the camera it keeps, moved by the pointer."""

        def __init__(self, surface, size, render_options):
            super().__init__(css_width=f"{size[0]}px", css_height=f"{size[1]}px")
            self.surface = surface
            self.size = tuple(size)
            self.render_options = render_options
            self.camera = None  # a dict of camera settings; None frames the surface
            self._drag = None
            self.frames = 0

        def _render_settings(self):
            keys = _settings.keys(("render",))
            return _settings.settings({k: v for k, v in {**self.render_options, **(self.camera or {})}.items() if k in keys},
                                      keys, "view")

        def move(self, how, a=0.0, b=0.0):
            """Moves the camera ("orbit" yaw, pitch degrees; "pan" dx, dy pixels; "dolly"
            factor) and draws again."""
            self.camera = _octrace.move_camera(self.surface._shell, self._render_settings() + [("size", f"{self.size[0]}x{self.size[1]}")],
                                               how, float(a), float(b), int(self.size[1]))
            self.request_draw()

        def handle_event(self, event):
            kind = event.get("event_type") or event.get("type")
            if kind == "resize":
                self.size = (max(1, int(event["width"])), max(1, int(event["height"])))
            elif kind == "pointer_down":
                pan = event.get("button") == 3 or "Shift" in event.get("modifiers", ())
                self._drag = (event["x"], event["y"], "pan" if pan else "orbit")
            elif kind == "pointer_move" and self._drag:
                x0, y0, how = self._drag
                dx, dy = event["x"] - x0, event["y"] - y0
                self._drag = (event["x"], event["y"], how)
                if how == "orbit":
                    self.move("orbit", dx * 0.4, dy * 0.4)  # the studio's degrees per pixel
                else:
                    self.move("pan", dx, dy)
            elif kind == "pointer_up":
                self._drag = None
            elif kind == "wheel":
                self.move("dolly", 1.1 ** (event.get("dy", 0.0) / 100.0))

        def get_frame(self):
            img = self.surface.render(size=self.size, **{**self.render_options, **(self.camera or {})})
            self.frames += 1
            return img.rgba

    if isinstance(source, Surface):
        return SurfaceView(source, size, options)
    steps = None
    if type(source).__name__ == "DataArray" and hasattr(source, "octrace"):
        steps = _Steps(source, dim, options)
        options = steps.rest
        source = steps.volume(0)
    elif dim is not None:
        raise _octrace.UsageError("'dim' steps through a DataArray's dimension: give a DataArray")
    if not isinstance(source, Volume):
        raise TypeError(f"view() shows a Surface, a Volume or an xarray DataArray, got {type(source).__name__}")

    import ipywidgets

    render_keys = _settings.keys(("render", "figure"), shading=True)
    render_options = {k: v for k, v in options.items() if k in render_keys}
    build_options = {k: v for k, v in options.items() if k not in render_keys}
    lo, hi = iso_range if iso_range is not None else source.valid_range  # a DataArray's: its first step's
    start = iso if iso is not None else (lo + hi) / 2
    frame = SurfaceView(source.surface(iso=start, **build_options), size, render_options)
    frame.volume = source
    slider = ipywidgets.FloatSlider(value=start, min=lo, max=hi, step=(hi - lo) / 200, description="iso",
                                    continuous_update=False)

    def rebuild(change):
        frame.surface = frame.volume.surface(iso=slider.value, **build_options)
        frame.request_draw()

    slider.observe(rebuild, names="value")
    controls = [frame, slider]
    box = ipywidgets.VBox()
    box.frame, box.slider, box.step_slider = frame, slider, None  # for scripts and tests
    if steps is not None:
        step_slider = ipywidgets.IntSlider(value=0, min=0, max=steps.count - 1, description=steps.dim,
                                           continuous_update=False)
        label = ipywidgets.Label(steps.caption(0))

        def step(change):
            if frame.camera is None:  # keep the view the first step framed while the surface changes
                frame.camera = _octrace.move_camera(frame.surface._shell, frame._render_settings()
                                                    + [("size", f"{frame.size[0]}x{frame.size[1]}")], "", 0.0, 0.0,
                                                    int(frame.size[1]))
            frame.volume = steps.volume(change["new"])
            label.value = steps.caption(change["new"])
            rebuild(None)

        step_slider.observe(step, names="value")
        controls.append(ipywidgets.HBox([step_slider, label]))
        box.step_slider, box.step_label = step_slider, label
    box.children = controls
    return box


class _Steps:
    """A DataArray's steps along one dimension, each read as ``da.octrace.volume()`` reads it."""

    def __init__(self, da, dim, options):
        from ._xarray import _split

        spatial = 3
        if dim is None:
            extra = [d for d in da.dims if d == "time"] or (list(da.dims[:-spatial]) if da.ndim > spatial else [])
            if not extra:
                raise _octrace.UsageError(f"the DataArray has no dimension to step through ({', '.join(map(str, da.dims))}): "
                                          "view a Volume (da.octrace.volume()) instead, or give 'dim'")
            dim = extra[0]
        if dim not in da.dims:
            raise _octrace.UsageError(f"{dim!r} is not a dimension of the DataArray (it has {', '.join(map(str, da.dims))})")
        if da.sizes[dim] == 0:
            raise _octrace.UsageError(f"{dim!r} has no steps")
        self.da, self.dim, self.count = da, dim, da.sizes[dim]
        self.reader, self.rest = _split(options)
        self._volumes = {}
        self._captions = None

    def volume(self, i):
        if i not in self._volumes:
            self._volumes = {i: self.da.isel({self.dim: i}).octrace.volume(**self.reader)}  # one step held at a time
        return self._volumes[i]

    def caption(self, i):
        if self._captions is None:
            from ._animate import captions

            self._captions = captions(self.da, self.dim)
        return self._captions[i]

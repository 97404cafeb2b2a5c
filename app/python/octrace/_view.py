"""An interactive view in Jupyter without GL: octrace renders each frame on the CPU and
jupyter_rfb (a remote frame buffer) shows it. Drag to orbit, Shift+drag or the middle button to
pan, the wheel to zoom, as in the studio (the same camera moves: octrace/model/Navigation.h).
Given a Volume, an iso slider rebuilds the surface."""

from __future__ import annotations

from . import _octrace, _settings


def _require_rfb():
    try:
        import jupyter_rfb
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError("octrace.view needs jupyter_rfb (pip install jupyter_rfb)") from e
    return jupyter_rfb


def view(source, *, size=(640, 480), iso=None, iso_range=None, **options):
    """A widget showing ``source`` (a Surface, or a Volume whose surface the ``iso`` slider
    rebuilds over ``iso_range``, default the volume's valid range). ``options`` are render()'s
    (renderer, background, colormap, ...) and, for a Volume, surface()'s (depth, ...)."""
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
    if not isinstance(source, Volume):
        raise TypeError(f"view() shows a Surface or a Volume, got {type(source).__name__}")

    import ipywidgets

    render_keys = _settings.keys(("render", "figure"), shading=True)
    render_options = {k: v for k, v in options.items() if k in render_keys}
    build_options = {k: v for k, v in options.items() if k not in render_keys}
    lo, hi = iso_range if iso_range is not None else source.valid_range
    start = iso if iso is not None else (lo + hi) / 2
    frame = SurfaceView(source.surface(iso=start, **build_options), size, render_options)
    slider = ipywidgets.FloatSlider(value=start, min=lo, max=hi, step=(hi - lo) / 200, description="iso",
                                    continuous_update=False)

    def rebuild(change):
        frame.surface = source.surface(iso=change["new"], **build_options)
        frame.request_draw()

    slider.observe(rebuild, names="value")
    box = ipywidgets.VBox([frame, slider])
    box.frame, box.slider = frame, slider  # for scripts and tests
    return box

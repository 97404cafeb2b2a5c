"""Animations of a DataArray over one of its dimensions: one surface per step, one fixed camera
(or an orbit), the step's coordinate value in each figure's caption, frames rendered in
parallel — on local threads (the GIL is released while building and rendering), or one task
per frame on a Dask distributed Client (a LocalCluster, or dask-jobqueue's SLURM/PBS clusters)
— and joined into an MP4 by octrace's video writer (FFmpeg's libraries, io/VideoWriter.h).
The CLI's `octrace animate` does the same for a file's time steps (model/Animation.h)."""

from __future__ import annotations

import concurrent.futures
import os
import sys

import numpy as np

from . import _octrace, _settings


def _caption(value):
    """A coordinate value as a caption: a date as YYYY-MM-DD (with the time when it has one)."""
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value[()]
    if isinstance(value, np.datetime64):
        text = np.datetime_as_string(value, unit="s")
        return text[:10] if text.endswith("T00:00:00") else text.replace("T", " ")
    if hasattr(value, "calendar") and hasattr(value, "isoformat"):  # cftime
        text = value.isoformat()
        return text[:10] if text.endswith("T00:00:00") or text.endswith(" 00:00:00") else text
    if isinstance(value, (float, np.floating)):
        return f"{value:g}"
    return str(value)


def captions(da, dim):
    """The caption of each step of ``da`` along ``dim``: its date (decoded datetimes, cftime
    dates, or numbers in CF "UNIT since DATE" units that xarray left undecoded, e.g. a year-0
    climatology opened with decode_times=False, dated by the NetCDF reader's own calendars),
    else its coordinate value, else "step I"."""
    if dim not in da.coords:
        return [f"step {i}" for i in range(da.sizes[dim])]
    coord = da[dim]
    values = coord.values
    units = coord.attrs.get("units", coord.encoding.get("units"))
    if values.dtype.kind in "iuf" and isinstance(units, str) and " since " in units:
        calendar = coord.attrs.get("calendar", coord.encoding.get("calendar", "")) or ""
        try:
            return list(_octrace.cf_dates([float(v) for v in values], units, str(calendar), f"coordinate {dim!r}"))
        except _octrace.FileError as e:
            _settings._LOG.warning(f"{e}: captions give the numbers")
    return [_caption(v) for v in values]


def _frame(da, reader, build, view, camera, caption, png):
    """One frame (a top-level function, so that Dask can send it to another process): the
    DataArray's step through the accessor, its surface, the frame from `camera`."""
    import octrace  # noqa: F401 - registers the accessor in a fresh worker

    shell = da.octrace.surface(**reader, **build)
    options = dict(view)
    if options.get("figure"):
        options["caption"] = caption
    img = shell.render(camera=camera, **options)
    if png:
        img.save(png)
    return np.array(img)  # a copy: it outlives the frame and crosses processes


def _progress(total, enabled):
    if callable(enabled):  # the caller's own: called with the fraction done, as surface()'s
        return lambda done: enabled(done / total)
    if not enabled:
        return lambda done: None
    try:
        from tqdm.auto import tqdm

        bar = tqdm(total=total, desc="octrace animate", unit="frame")
        return lambda done: (bar.update(done - bar.n), bar.close() if done >= total else None)
    except ImportError:
        def show(done):
            print(f"\roctrace: animate {done}/{total} frames", end="\n" if done >= total else "", file=sys.stderr, flush=True)
        return show


def animate(da, dim="time", path=None, *, frames=None, fps=None, orbit=0.0, size=(960, 720), client=None, workers=None,
            progress=True, **options):
    """Renders one frame per step of ``da`` along ``dim`` and writes them to ``path`` (an MP4,
    H.264) and/or PNGs in the folder ``frames``. ``options``: the surface's (iso, depth,
    colormap, colour_range, ...), the reader's (region, depth_range, vertical_scale) and
    render's (camera, renderer, background, figure=True with title, ...). The camera frames
    the first step's grid, which every step shares, and turns ``orbit`` degrees over the
    animation; with ``figure=True`` each frame's subtitle starts with its coordinate value.
    ``client``: a dask.distributed Client, one task per frame; otherwise ``workers`` local
    threads (default: one per core). ``fps``: frames a second (the options table's default).
    ``progress``: True shows a bar (tqdm when installed, else a line on stderr), False nothing,
    a callable is called with the fraction of frames done, and an exception it raises (e.g.
    KeyboardInterrupt) cancels the frames not yet drawn and writes nothing. Returns the path
    of the video (or of the frames' folder)."""
    if type(da).__name__ == "Dataset":
        raise _octrace.UsageError("a Dataset holds several variables: animate one, e.g. octrace.animate(ds['TEMP'], ...)")
    if dim not in da.dims:
        raise _octrace.UsageError(f"{dim!r} is not a dimension of the DataArray (it has {', '.join(map(str, da.dims))})")
    if path is None and frames is None:
        raise _octrace.UsageError("give a video 'path' (.mp4) or a 'frames' folder, or both")
    if path is not None and not os.fspath(path).lower().endswith(".mp4"):
        raise _octrace.UsageError(f"'{os.fspath(path)}': an animation is written as .mp4")
    fps = int(_octrace.parse_number("fps", str(fps if fps is not None else int(_settings.default("fps")))))
    orbit = _octrace.parse_number("orbit", repr(float(orbit)))
    camera = dict(options.pop("camera", None) or {})
    reader_keys = _settings.reader_keys() - {"var", "series", "time", "volume"}
    view_keys = _settings.keys(("render", "figure"), shading=True)
    reader = {k: v for k, v in options.items() if k in reader_keys}
    view = {k: v for k, v in options.items() if k in view_keys}
    build = {k: v for k, v in options.items() if k not in reader_keys and k not in view_keys}
    view["size"] = size
    # Every keyword checked before any work, as the calls below will take them.
    _settings.settings(reader, reader_keys, "animate")
    _settings.settings(build, _settings.keys(("surface",)), "animate")
    render_settings = _settings.settings({**view, **camera}, view_keys, "animate")

    steps = da.sizes[dim]
    if steps == 0:
        raise _octrace.UsageError(f"{dim!r} has no steps")
    grid = da.isel({dim: 0}).octrace.volume(**reader)
    given = {**build, **view}
    if given.get("colormap") is not None and given.get("colour_range") is None and given.get("window") is None:
        # Coloured by height: over the grid's heights in every frame, as octrace animate does.
        view["colour_range"] = tuple(_octrace.height_range(grid._field))
        _settings._LOG.info(f"coloured by height over the grid: [{view['colour_range'][0]:g}, {view['colour_range'][1]:g}]"
                            " the same in every frame ('colour_range' sets it)")
    view_only = [(k, t) for k, t in render_settings if k in _settings.keys(("render",))]
    cameras = [_octrace.box_camera(grid.bounds, view_only, orbit * i / steps) for i in range(steps)]
    texts = captions(da, dim)
    pngs = [None] * steps
    if frames is not None:
        os.makedirs(frames, exist_ok=True)
        pngs = [os.path.join(os.fspath(frames), f"frame_{i:04d}.png") for i in range(steps)]
    args = [(da.isel({dim: i}), reader, build, view, cameras[i], texts[i], pngs[i]) for i in range(steps)]

    show = _progress(steps, progress)
    video = _Video(path, fps)
    if client is not None:
        from dask.distributed import as_completed

        futures = [client.submit(_frame, *a, key=f"octrace-frame-{i}-{id(args)}", pure=False) for i, a in enumerate(args)]
        index = {f.key: i for i, f in enumerate(futures)}
        try:
            for done, future in enumerate(as_completed(futures), start=1):
                video.put(index[future.key], future.result())
                future.release()
                show(done)
        except BaseException:
            client.cancel(futures)
            video.abandon()
            raise
    else:
        with concurrent.futures.ThreadPoolExecutor(max_workers=workers or os.cpu_count() or 1) as pool:
            futures = {pool.submit(_frame, *a): i for i, a in enumerate(args)}
            try:
                for done, future in enumerate(concurrent.futures.as_completed(futures), start=1):
                    video.put(futures[future], future.result())
                    show(done)
            except BaseException:
                for future in futures:
                    future.cancel()
                video.abandon()
                raise
    video.finish()
    _settings.flush_log()
    return os.fspath(path) if path is not None else os.fspath(frames)


class _Video:
    """Frames into the MP4 in order as they arrive (any order): a frame is encoded as soon as
    every earlier one has been, so that encoding overlaps the rendering and only the frames
    that arrived early are held."""

    def __init__(self, path, fps):
        self.path, self.fps = path, fps
        self.writer = None
        self.waiting = {}
        self.next = 0

    def put(self, i, image):
        if self.path is None:
            return
        self.waiting[i] = image
        while self.next in self.waiting:
            image = self.waiting.pop(self.next)
            if self.writer is None:
                height, width = image.shape[:2]
                self.writer = _octrace.VideoWriter(os.fspath(self.path), width, height, self.fps)
            self.writer.add(image)
            self.next += 1

    def finish(self):
        if self.writer is not None:
            self.writer.finish()

    def abandon(self):
        self.writer = None  # the encoded video is held in memory until finish(): nothing is written

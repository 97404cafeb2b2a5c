"""What the benchmark scripts that draw plots share: the record of the machine and commit a run
was measured on (written as run.json beside the raw JSON), the caption line made from it, and the
time-against-rays figure of bench/figure5.py and bench/figure5_2d.py, drawn with matplotlib.

matplotlib is Debian's python3-matplotlib (scripts/setup.sh installs it), so these scripts run
with the system interpreter, /usr/bin/python3, not the project's virtual environment."""
import argparse
import datetime
import json
import math
import os
import platform
import subprocess
import sys
import textwrap

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RUN_JSON = "run.json"


def _cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def _commit():
    """This checkout's commit (short hash), with "+changes" when the tree differs from it."""
    def git(*args):
        return subprocess.run(["git", "-C", ROOT, *args], capture_output=True, text=True)
    head = git("rev-parse", "--short", "HEAD")
    if head.returncode != 0:
        return "unknown (not a git checkout)"
    dirty = git("status", "--porcelain", "--untracked-files=no").stdout.strip()
    return head.stdout.strip() + ("+changes" if dirty else "")


def add_plot_options(ap, name):
    """--plot-only, --raw and --out, for a script writing docs/benchmarks/NAME.md and NAME.png from
    the raw JSON in docs/benchmarks/NAME/; the --out folder is created when the options are read."""
    docs = os.path.join(ROOT, "docs", "benchmarks")

    class OutDir(argparse.Action):
        def __call__(self, parser, namespace, value, option_string=None):
            os.makedirs(value, exist_ok=True)
            setattr(namespace, self.dest, value)
    ap.add_argument("--plot-only", action="store_true", help="redraw the plot and Markdown from the raw JSON, measure nothing")
    ap.add_argument("--raw", default=os.path.join(docs, name), help="the raw JSON folder (default docs/benchmarks/%s)" % name)
    ap.add_argument("--out", default=docs, action=OutDir, help="where %s.md and %s.png go (default docs/benchmarks)" % (name, name))


def start_run(**settings):
    """The record of a run about to be measured: machine, commit, date, load; settings added."""
    run = {"cpu": _cpu_model(), "cores": os.cpu_count(), "platform": platform.platform(), "commit": _commit(),
           "date_utc": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M"),
           "load_average_start": [round(x, 2) for x in os.getloadavg()]}
    run.update(settings)
    return run


def finish_run(run, raw_dir):
    """Adds the load average at the end and writes RAW_DIR/run.json."""
    run["load_average_end"] = [round(x, 2) for x in os.getloadavg()]
    with open(os.path.join(raw_dir, RUN_JSON), "w") as f:
        json.dump(run, f, indent=2)
        f.write("\n")


def load_run(raw_dir):
    """RAW_DIR/run.json, or None when there is none."""
    path = os.path.join(raw_dir, RUN_JSON)
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return json.load(f)


def caption(run, how):
    """One line: the machine and commit the raw JSON records, then HOW the points were measured.
    Raw data measured before runs were recorded carry a run.json with "recorded": false, saying
    what is known of them instead: the cores the page named, the commit that brought the JSON."""
    if run is None:
        where = "Machine and commit: not recorded with these raw data"
    elif not run.get("recorded", True):
        where = ("Machine: %d cores (%s), CPU model not recorded; build commit not recorded, raw JSON committed in "
                 "%s (%s UTC)") % (run["cores"], run["cores_source"], run["committed_in"], run["committed_utc"])
    else:
        where = "Machine: %s, %d cores; commit %s; %s UTC, load average %.1f to %.1f" % (
            run["cpu"], run["cores"], run["commit"], run["date_utc"], run["load_average_start"][0],
            run["load_average_end"][0])
    return "%s; %s." % (where, how)


def _pyplot():
    try:
        import matplotlib
    except ImportError:
        sys.exit("%s: matplotlib is missing for %s: install Debian's python3-matplotlib (scripts/setup.sh) and run "
                 "the script with /usr/bin/python3" % (os.path.basename(sys.argv[0]), sys.executable))
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


# One colour per scene, one line style and marker per tracer.
SCENE_COLOURS = ["#c0392b", "#1f5fb4", "#2e8b57", "#8e44ad", "#d35400", "#5d6d7e"]
TRACER_STYLES = {"beam": ("-", "o"), "Samet": ("--", "s")}


def _tick_text(v):
    """A tick value as a reader writes it: 0.001, 20, 5,000, 2,000,000."""
    return format(int(round(v)), ",") if v >= 1 else "%g" % v


def _log_axis(ax, which, values):
    """AX's WHICH ("x" or "y") axis logarithmic, with its values written out: every 1, 2, 5 of a decade labelled when the
    data span at most two decades, only the decades otherwise (the rest are unlabelled ticks)."""
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter
    getattr(ax, "set_%sscale" % which)("log")
    axis = getattr(ax, which + "axis")
    span = math.log10(max(values)) - math.log10(min(values))
    subs = (1.0, 2.0, 5.0) if span <= 2 else (1.0,)
    axis.set_major_locator(LogLocator(base=10, subs=subs))
    axis.set_major_formatter(FuncFormatter(lambda v, _: _tick_text(v)))
    axis.set_minor_locator(LogLocator(base=10, subs=[k for k in range(2, 10) if k not in subs]))
    axis.set_minor_formatter(NullFormatter())


def time_against_rays(path, title, scenes, xlabel, caption_line, target=None, point_labels=None):
    """Writes PATH, a PNG of two panels sharing a logarithmic ray axis: left the time of each
    tracer (log-log), right Samet's time over the beam's (linear), with 1x and TARGET marked.

    scenes: [(name, [(rays, beam_ms, samet_ms), ...])]; point_labels: a label per point of the
    right panel (e.g. rays per pixel), the same for every scene, or None."""
    plt = _pyplot()

    fig, (ax_t, ax_r) = plt.subplots(1, 2, figsize=(11, 5.0), dpi=100)
    for i, (name, pts) in enumerate(scenes):
        colour = SCENE_COLOURS[i % len(SCENE_COLOURS)]
        rays = [p[0] for p in pts]
        for tracer, column in (("beam", 1), ("Samet", 2)):
            ls, marker = TRACER_STYLES[tracer]
            ax_t.plot(rays, [p[column] for p in pts], ls=ls, marker=marker, color=colour, ms=5, lw=1.6,
                      label="%s: %s" % (name, tracer))
        ratio = [p[2] / p[1] for p in pts]
        ax_r.plot(rays, ratio, "-o", color=colour, ms=5, lw=1.6, label=name)
        if point_labels:
            for x, y, text in zip(rays, ratio, point_labels):
                ax_r.annotate(text, (x, y), textcoords="offset points", xytext=(-5, 6), ha="right", fontsize=8,
                              color=colour)

    rays = [p[0] for _, pts in scenes for p in pts]
    for ax in (ax_t, ax_r):
        _log_axis(ax, "x", rays)
        ax.set_xlim(min(rays) / 1.8, max(rays) * 1.3)  # room for the point labels left of the first points
        ax.set_xlabel(xlabel + ", log scale")
        ax.grid(True, which="major", color="#bbbbbb", lw=0.8)
        ax.grid(True, which="minor", color="#e6e6e6", lw=0.5)
    _log_axis(ax_t, "y", [p[c] for _, pts in scenes for p in pts for c in (1, 2)])
    ax_t.set_ylabel("time (ms), log scale")
    ax_t.set_title("Time of each tracer")
    ax_t.legend(fontsize=8, loc="upper left")

    ax_r.axhline(1.0, color="#555555", lw=1, ls=":", label="1x: equal times")
    if target is not None:
        value, text = target
        ax_r.axhline(value, color="#2e8b57", lw=1.2, ls="-.", label=text)
    ax_r.set_ylim(0, 1.3 * max([p[2] / p[1] for _, pts in scenes for p in pts] + [target[0] if target else 1]))
    ax_r.set_ylabel("Samet's time / beam's time, linear scale")
    ax_r.set_title("Speed-up of the beam over Samet")
    # "best" weighs the lines, not the point labels, which sit above and left of the points.
    ax_r.legend(fontsize=8, loc="lower right" if point_labels else "best")

    fig.suptitle(title, fontsize=12)
    fig.text(0.5, 0.015, textwrap.fill(caption_line, 170), ha="center", va="bottom", fontsize=8)
    fig.tight_layout(rect=(0, 0.06, 1, 0.95))
    fig.savefig(path)
    plt.close(fig)

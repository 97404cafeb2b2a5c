"""What bench/lighting.py, bench/memory.py and bench/process.py share: the repository root, JSON
reading, the common command-line options (octrace binary, data folder) with the raw-JSON folder,
and a scene's field options."""
import argparse
import json
import os
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def load(path):
    with open(path) as f:
        return json.load(f)


def parser(doc):
    """An argument parser with --octrace and --data (defaults: this tree's build, ../shared/data)."""
    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--octrace", default=os.path.join(ROOT, "build", "app", "octrace"))
    ap.add_argument("--data", default=os.path.join(ROOT, "..", "shared", "data"))
    return ap


def field_args(scene, data):
    """The input and field options of a bench/scenes NetCDF scene: the file under DATA, --var,
    --iso and --region."""
    return [os.path.join(data, scene["input"]), "--var", scene["var"], "--iso", str(scene["iso"]), "--region",
            scene["region"]]


def raw_dir(name):
    """docs/benchmarks/NAME/, created."""
    d = os.path.join(ROOT, "docs", "benchmarks", name)
    os.makedirs(d, exist_ok=True)
    return d


def run_recording_load(cmd, stats):
    """Runs CMD (which writes the JSON file STATS) and adds to that JSON the 1-minute load
    average before and after the run ("load_avg_1min"); returns the JSON."""
    load0 = os.getloadavg()[0]
    subprocess.run(cmd, check=True)
    load1 = os.getloadavg()[0]
    st = load(stats)
    st["load_avg_1min"] = [round(load0, 2), round(load1, 2)]
    with open(stats, "w") as f:
        json.dump(st, f, indent=2)
        f.write("\n")
    return st

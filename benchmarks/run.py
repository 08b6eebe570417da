#!/usr/bin/python3
"""The skylayers benchmark harness: scenes x resolutions x variants, timed in one run.

    benchmarks/run.py                      # the matrix of benchmarks/matrix.json -> benchmarks/results/
    benchmarks/run.py --smoke --out DIR    # a tiny configuration (CI)
    benchmarks/run.py --compare still temporal --scene peer_view --resolution 640x360
    benchmarks/run.py --baseline OTHER/skybench    # this build against another, frame by frame

It also times skyview's slow pan in a window under Xvfb (the matrix's "window" entry).

See benchmarks/README.md. It drives skybench (benchmarks/skybench.cpp), a frame server that
keeps a build's Vulkan context warm, over JSON lines; Debian's /usr/bin/python3 and its
python3-matplotlib (scripts/install-deps.sh) are all it needs.
"""
import argparse
import csv
import datetime
import json
import math
import os
import platform
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import threading
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


class HarnessError(Exception):
    """A one-line error for the user (bad matrix, missing build, a failed frame)."""


class Worker:
    """One skybench process: a build of skylayers, kept warm between requests."""

    def __init__(self, binary, label, env):
        if not os.path.isfile(binary) or not os.access(binary, os.X_OK):
            raise HarnessError(f"{binary}: no skybench binary there (build it: cmake --build "
                               f"--preset release --target skybench)")
        self.label = label
        self.binary = binary
        self.env = env
        self.validation = []  # Vulkan validation messages the worker printed
        self.kept_references = {}  # reference case name -> seconds its frame took
        self.stderr = []
        self.proc = subprocess.Popen([binary], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                     stderr=subprocess.PIPE, text=True, cwd=ROOT, env=env)
        self._reader = threading.Thread(target=self._read_stderr, daemon=True)
        self._reader.start()
        hello = self.request({"op": "hello"})
        self.device = hello["device"]
        self.version = hello["version"]

    def _read_stderr(self):
        for line in self.proc.stderr:
            line = line.rstrip("\n")
            self.stderr.append(line)
            if "Vulkan validation" in line:
                self.validation.append(line)

    def request(self, message):
        self.proc.stdin.write(json.dumps(message) + "\n")
        self.proc.stdin.flush()
        line = self.proc.stdout.readline()
        if not line:
            tail = "; ".join(self.stderr[-3:])
            raise HarnessError(f"skybench ({self.label}) ended during {message.get('op')}: {tail}")
        reply = json.loads(line)
        if not reply.get("ok"):
            raise HarnessError(f"skybench ({self.label}): {message.get('op')} "
                               f"{message.get('case', '')}: {reply.get('error')}")
        return reply

    def close(self):
        if self.proc.poll() is None:
            try:
                self.proc.stdin.write(json.dumps({"op": "quit"}) + "\n")
                self.proc.stdin.close()
                self.proc.wait(timeout=30)
            except (BrokenPipeError, subprocess.TimeoutExpired):
                self.proc.kill()
        self._reader.join(timeout=5)


def parse_resolution(text):
    m = re.fullmatch(r"(\d+)x(\d+)", text)
    if not m:
        raise HarnessError(f"resolution '{text}': expected WIDTHxHEIGHT, e.g. 1280x720")
    return int(m.group(1)), int(m.group(2))


def stats(values):
    return {"min": min(values), "median": statistics.median(values), "max": max(values)}


def open_case(worker, name, scene, variant, resolution, first_frame=0):
    width, height = parse_resolution(resolution)
    worker.request({
        "op": "open", "case": name, "scene": os.path.join(ROOT, scene["scene"]),
        "set": scene.get("set", []) + variant.get("set", []), "width": width, "height": height,
        "heading_deg_per_frame": scene.get("heading_deg_per_frame", 0.0),
        "seconds_per_frame": scene.get("seconds_per_frame", 0.0), "first_frame": first_frame,
        "views": variant.get("views", 1), "views_mode": variant.get("views_mode", "one_frame")})


def frame_record(reply):
    return {"frame": reply["frame"], "frame_ms": reply["frame_ms"], "render_ms": reply["render_ms"],
            "display_ms": reply["display_ms"], "gpu_ms": reply["gpu_ms"],
            "passes": {p["name"]: p["gpu_ms"] for p in reply["passes"]},
            # The largest image each pass writes: which empty pass it is measured against.
            "pass_texels": {p["name"]: p.get("texels", 0) for p in reply["passes"]}}


def summarise(frames):
    passes = {}
    for f in frames:
        for name, ms in f["passes"].items():
            passes.setdefault(name, []).append(ms)
    texels = {}
    for f in frames:
        texels.update(f.get("pass_texels", {}))
    return {"frame_ms": stats([f["frame_ms"] for f in frames]),
            "render_ms": stats([f["render_ms"] for f in frames]),
            "gpu_ms": stats([f["gpu_ms"] for f in frames]),
            "pass_texels": texels,
            # A pass absent from some frames (a light volume refreshed now and then) counts
            # 0 there, so the medians add up to what a frame costs.
            "pass_median_ms": {n: statistics.median(v + [0.0] * (len(frames) - len(v)))
                               for n, v in passes.items()}}


class Harness:
    def __init__(self, matrix, workers, out_dir, log):
        self.matrix = matrix
        self.workers = workers  # {"a": Worker, optionally "b": Worker}
        self.out_dir = out_dir
        self.log = log
        self.cases = []
        self.comparisons = []
        self.validation_seen = []  # messages of workers already restarted

    def restart(self, key):
        old = self.workers[key]
        old.close()
        self.validation_seen.extend(old.validation)
        self.workers[key] = Worker(old.binary, old.label, old.env)

    def scene(self, name):
        try:
            return self.matrix["scenes"][name]
        except KeyError:
            raise HarnessError(f"scene '{name}' is not in the matrix "
                               f"(scenes: {', '.join(self.matrix['scenes'])})")

    def variant(self, name):
        try:
            return self.matrix["variants"][name]
        except KeyError:
            raise HarnessError(f"variant '{name}' is not in the matrix "
                               f"(variants: {', '.join(self.matrix['variants'])})")

    def counts(self, scene):
        return (scene.get("warmup", self.matrix.get("warmup", 2)),
                scene.get("frames", self.matrix.get("frames", 5)))

    def quality_frames(self, scene, warmup, frames):
        last = warmup + frames - 1
        wanted = scene.get("quality_frames", [last])
        return sorted({min(max(int(k), 0), last) for k in wanted})

    def reference(self, worker, scene_name, resolution, frame, case_name):
        """Renders the reference march of `scene_name` at `frame` and compares `case_name`'s
        last frame with it. A reference is rendered once per scene, resolution and frame and
        kept open in the worker: the variants of a scene (the pan's two) share it, and at
        1280x720 each costs about a minute."""
        ref_name = f"{scene_name}_{resolution}_f{frame:03d}@ref"
        kept = worker.kept_references
        if ref_name not in kept:
            open_case(worker, ref_name, self.scene(scene_name), self.variant(
                self.matrix.get("reference_variant", "reference")), resolution,
                first_frame=frame)
            t0 = time.monotonic()
            worker.request({"op": "frame", "case": ref_name})
            kept[ref_name] = time.monotonic() - t0
        ref_s = kept[ref_name]
        q = worker.request({"op": "quality", "case": case_name, "reference": ref_name})
        if self.out_dir:
            worker.request({"op": "save", "case": ref_name, "png": os.path.join(
                self.out_dir, "images", f"{case_name}_f{frame:03d}_reference.png")})
        return {"frame": frame, "psnr_db": q["psnr_db"], "max_error": q["max_error"],
                "mean_error": q["mean_error"], "reference_s": ref_s}

    def run_case(self, scene_name, resolution, variant_name, quality):
        scene, variant = self.scene(scene_name), self.variant(variant_name)
        worker = self.workers["a"]
        name = f"{scene_name}_{resolution}_{variant_name}"
        warmup, frames = self.counts(scene)
        self.log(f"{name}: {warmup} warm-up + {frames} frames")
        open_case(worker, name, scene, variant, resolution)
        wanted = self.quality_frames(scene, warmup, frames) if quality else []
        records, qualities = [], []
        for k in range(warmup + frames):
            reply = worker.request({"op": "frame", "case": name})
            if k >= warmup:
                records.append(frame_record(reply))
            if k in wanted:
                qualities.append(self.reference(worker, scene_name, resolution, k, name))
                self.log(f"  frame {k}: {qualities[-1]['psnr_db']:.1f} dB against the reference")
        if self.out_dir:
            worker.request({"op": "save", "case": name,
                            "png": os.path.join(self.out_dir, "images", f"{name}.png")})
        worker.request({"op": "close", "case": name})
        w, h = parse_resolution(resolution)
        case = {"scene": scene_name, "resolution": resolution, "pixels": w * h,
                "variant": variant_name, "warmup": warmup, "frames": records,
                "summary": summarise(records), "quality": qualities}
        self.log(f"  median {case['summary']['frame_ms']['median']:.0f} ms a frame")
        self.cases.append(case)
        return case

    def empty_pass(self, resolution, frames):
        """The yardstick of the per-pass goal: an empty full-screen pass (shaders/empty_pass.comp,
        which only writes its RGBA32F image) at `resolution`, timed `frames` times after one
        warm-up frame (the first touches the image's memory)."""
        w, h = parse_resolution(resolution)
        reply = self.workers["a"].request({"op": "empty", "width": w, "height": h,
                                           "frames": frames + 1})
        ms = reply["gpu_ms"][1:]
        entry = {"resolution": resolution, "pixels": w * h, "gpu_ms": stats(ms), "frames": ms}
        self.log(f"empty pass {resolution}: median {entry['gpu_ms']['median']:.2f} ms")
        return entry

    def timed_sequence(self, scene_name, resolution, variant_name):
        """A case's frames without the reference: what one side of an interleaved peer round
        costs. Returns its summary."""
        scene, variant = self.scene(scene_name), self.variant(variant_name)
        worker = self.workers["a"]
        name = f"round_{scene_name}_{resolution}_{variant_name}"
        warmup, frames = self.counts(scene)
        open_case(worker, name, scene, variant, resolution)
        records = []
        for k in range(warmup + frames):
            reply = worker.request({"op": "frame", "case": name})
            if k >= warmup:
                records.append(frame_record(reply))
        worker.request({"op": "close", "case": name})
        return summarise(records)

    def peer_rounds(self, spec, goal, rounds, log):
        """The peer and our goal case alternated, `rounds` times each (peer, ours, peer, ours,
        ...), so a machine that gets busier or quieter moves both sides of a round alike: each
        round's ratio is the peer's median frame over ours, and the figure is their median."""
        out = []
        for k in range(rounds):
            peer = run_peer(spec["resolution"], spec.get("frames", 5), log)
            if not peer:
                return None
            result = peer.get("results", {}).get(spec["resolution"])
            if not result:
                raise HarnessError(f"the peer's JSON has no result at {spec['resolution']}")
            # Ours in a fresh skybench, as every group of cases.
            self.restart("a")
            ours = self.timed_sequence(goal["scene"], goal["resolution"], goal["variant"])
            ratio = result["median_ms"] / ours["frame_ms"]["median"]
            log(f"round {k + 1}: peer {result['median_ms']:.0f} ms, ours "
                f"{ours['frame_ms']['median']:.0f} ms a frame: {ratio:.1f}x")
            out.append({"peer_median_ms": result["median_ms"], "peer": peer,
                        "ours_median_ms": ours["frame_ms"]["median"], "ours": ours,
                        "speedup": ratio})
        return out

    def compare(self, scene_name, resolution, variant_a, variant_b):
        """Alternates frames of A and B (two variants, or one variant on two builds) and
        records B's time over A's frame by frame."""
        scene = self.scene(scene_name)
        wa = self.workers["a"]
        wb = self.workers.get("b", wa)
        na = f"cmp_{scene_name}_{resolution}_{variant_a}_{wa.label}"
        nb = f"cmp_{scene_name}_{resolution}_{variant_b}_{wb.label}"
        warmup, frames = self.counts(scene)
        self.log(f"compare {na} / {nb}: {warmup} warm-up + {frames} pairs")
        open_case(wa, na, scene, self.variant(variant_a), resolution)
        open_case(wb, nb, scene, self.variant(variant_b), resolution)
        ra, rb = [], []
        for k in range(warmup + frames):
            # Who goes first alternates, so neither always runs on a machine the other warmed.
            order = [(wa, na, ra), (wb, nb, rb)] if k % 2 == 0 else [(wb, nb, rb), (wa, na, ra)]
            for worker, name, records in order:
                reply = worker.request({"op": "frame", "case": name})
                if k >= warmup:
                    records.append(frame_record(reply))
        for worker, name in ((wa, na), (wb, nb)):
            worker.request({"op": "close", "case": name})
        ratios = [b["frame_ms"] / a["frame_ms"] for a, b in zip(ra, rb)]
        result = {"scene": scene_name, "resolution": resolution,
                  "a": {"variant": variant_a, "build": wa.binary, "summary": summarise(ra),
                        "frames": ra},
                  "b": {"variant": variant_b, "build": wb.binary, "summary": summarise(rb),
                        "frames": rb},
                  "ratio_b_over_a": stats(ratios), "ratios": ratios}
        self.log(f"  B/A median {result['ratio_b_over_a']['median']:.3f} "
                 f"(min {min(ratios):.3f}, max {max(ratios):.3f})")
        self.comparisons.append(result)
        return result


def run_peer(resolution, frames, log):
    """takram three-clouds at the same view and resolution (../shared/peers/takram), copied
    out first since shared/ may be read-only. Returns its JSON or None when absent."""
    source = os.path.join(os.path.dirname(ROOT), "shared", "peers", "takram")
    if not os.path.isfile(os.path.join(source, "run.sh")):
        log("peer: ../shared/peers/takram/run.sh is not here; no peer figures")
        return None
    # Chromium and Node.js through the project's installer (only what is missing).
    subprocess.run([os.path.join(ROOT, "scripts", "install-deps.sh"), "--peer"], check=True,
                   stdout=sys.stderr)
    work = os.path.join(tempfile.gettempdir(), "skylayers-peer-takram")
    if not os.path.isdir(work):
        shutil.copytree(source, work, symlinks=True)
    env = dict(os.environ, RES=resolution, FRAMES=str(frames), WARMUP="3")
    log(f"peer: takram three-clouds at {resolution}, {frames} frames (a few minutes)")
    proc = subprocess.run([os.path.join(work, "run.sh")], cwd=work, env=env,
                          capture_output=True, text=True)
    lines = [l for l in proc.stdout.splitlines() if l.strip().startswith("{")]
    if proc.returncode != 0 or not lines:
        raise HarnessError(f"peer run.sh failed (exit {proc.returncode}): "
                           f"{proc.stderr.strip().splitlines()[-1:] or ''}")
    result = json.loads(lines[-1])
    shot = result.get("results", {}).get(resolution, {}).get("screenshot")
    if shot:
        result["screenshot_path"] = os.path.join(work, "out", shot)
    return result


def run_window(spec, skyview, env, log):
    """skyview as a person uses it: a window (under Xvfb) over a slow pan, its frame rate
    after the first frame (which marches every pixel) from its --report-fps line."""
    if not os.path.isfile(skyview):
        log(f"window: {skyview} is not built; no window figures")
        return None
    if not shutil.which("xvfb-run"):
        log("window: xvfb-run is missing (scripts/install-deps.sh installs xvfb); no window figures")
        return None
    width, height = parse_resolution(spec["resolution"])
    cmd = ["xvfb-run", "-a", "-s", "-screen 0 1920x1200x24", skyview,
           os.path.join(ROOT, spec["scene"]), "--width", str(width), "--height", str(height),
           "--frames", str(spec["frames"]), "--report-fps",
           "--script", f"pan {spec['pan_deg_per_frame']}"]
    for kv in spec.get("set", []):
        cmd += ["--set", kv]
    log(f"window: skyview {spec['scene']} {spec['resolution']}, {spec['frames']} frames of a "
        f"{spec['pan_deg_per_frame']} deg/frame pan")
    proc = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=900)
    if proc.returncode != 0:
        raise HarnessError(f"skyview failed (exit {proc.returncode}): "
                           f"{(proc.stderr.strip().splitlines() or ['?'])[-1]}")
    m = re.search(r"skyview: (\d+) frames in ([0-9.]+) s, ([0-9.]+) fps \(render (\d+) ms/frame, "
                  r"(\d+) rendered\); after the first: ([0-9.]+) fps", proc.stdout)
    if not m:
        raise HarnessError(f"skyview printed no --report-fps line: {proc.stdout[-300:]!r}")
    validation = [line for line in proc.stderr.splitlines() if "validation" in line.lower()]
    return {"scene": spec["scene"], "resolution": spec["resolution"], "set": spec.get("set", []),
            "pan_deg_per_frame": spec["pan_deg_per_frame"], "frames": int(m.group(1)),
            "seconds": float(m.group(2)), "fps_all": float(m.group(3)),
            "render_ms_mean": float(m.group(4)), "fps_after_first": float(m.group(6)),
            "goal_fps": spec.get("goal_fps"), "validation_messages": validation,
            "command": " ".join(cmd[:4] + [os.path.relpath(c, ROOT) if c.startswith(ROOT) else c
                                          for c in cmd[4:]])}


def run_first_frame(spec, skyrender, log):
    """The first frame of a process, as `skyrender render` pays it with its caches warm (the
    SPIR-V, the noise and high-cloud textures, and Mesa's own shader cache, left on here):
    rendered twice, the second run's report (render_costs) says how much of the frame was
    making pipelines, textures and LUT bakes rather than drawing."""
    if not os.path.isfile(skyrender):
        log(f"first frame: {skyrender} is not built; no first-frame figures")
        return None
    width, height = parse_resolution(spec["resolution"])
    env = dict(os.environ)
    env.pop("MESA_SHADER_CACHE_DISABLE", None)
    runs = []
    with tempfile.TemporaryDirectory(prefix="skylayers-first-frame-") as tmp:
        for k in range(spec.get("runs", 3)):
            out = os.path.join(tmp, str(k))
            cmd = [skyrender, "render", os.path.join(ROOT, spec["scene"]), "--out", out,
                   "--set", f"output.width={width}", "--set", f"output.height={height}",
                   "--set", "output.name=first"] + [a for kv in spec.get("set", [])
                                                   for a in ("--set", kv)]
            t0 = time.monotonic()
            proc = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=900)
            wall = time.monotonic() - t0
            if proc.returncode != 0:
                raise HarnessError(f"skyrender failed (exit {proc.returncode}): "
                                   f"{(proc.stderr.strip().splitlines() or ['?'])[-1]}")
            with open(os.path.join(out, "first.json")) as fh:
                report = json.load(fh)
            runs.append({"process_s": wall, "gpu_ms": report["gpu_ms_total"],
                         "costs": report["render_costs"]})
    # The first run may fill the caches; the others find them.
    warm = runs[1:] or runs
    setup = statistics.median(r["costs"]["setup_ms"] for r in warm)
    log(f"first frame {spec['resolution']}: setup {setup:.0f} ms (pipelines, textures, bakes)")
    return {"scene": spec["scene"], "resolution": spec["resolution"], "runs": runs,
            "setup_ms_median": setup, "goal_setup_ms": spec.get("goal_setup_ms"),
            "command": "skyrender render " + spec["scene"] + f" --set output.width={width} "
                       f"--set output.height={height}"}


def run_dataset_shards(spec, skyrender, log):
    """A dataset rendered by one process against the same dataset in `shards` processes at
    once (as GNU parallel or a Slurm array on one machine runs them) and merged: the total
    wall time of each, alternated `rounds` times (single, sharded, single, ...) with the
    caches warm, so both find the bakes in the cache and neither bakes (docs/datasets.md)."""
    if not os.path.isfile(skyrender):
        log(f"dataset shards: {skyrender} is not built; no figures")
        return None
    spec_path = os.path.join(ROOT, spec["spec"])
    shards = spec.get("shards", 4)
    env = dict(os.environ)
    env.pop("MESA_SHADER_CACHE_DISABLE", None)
    rounds = []

    def timed(cmds):
        t0 = time.monotonic()
        procs = [subprocess.Popen(c, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                                  env=env) for c in cmds]
        for p, c in zip(procs, cmds):
            _, err = p.communicate(timeout=1800)
            if p.returncode != 0:
                raise HarnessError(f"{' '.join(c[:2])} failed (exit {p.returncode}): "
                                   f"{(err.strip().splitlines() or ['?'])[-1]}")
        return time.monotonic() - t0

    with tempfile.TemporaryDirectory(prefix="skylayers-dataset-shards-") as tmp:
        # A first run fills the caches (SPIR-V, textures, Mesa's shader cache); not timed.
        timed([[skyrender, "dataset", spec_path, "--out", os.path.join(tmp, "warm")]])
        for k in range(spec.get("rounds", 2)):
            single = os.path.join(tmp, f"single{k}")
            sharded = os.path.join(tmp, f"sharded{k}")
            t_single = timed([[skyrender, "dataset", spec_path, "--out", single]])
            t_sharded = timed([[skyrender, "dataset", spec_path, "--out", sharded, "--shard",
                                f"{i}/{shards}"] for i in range(1, shards + 1)])
            t_sharded += timed([[skyrender, "merge", sharded]])
            rounds.append({"single_s": t_single, "sharded_s": t_sharded,
                           "ratio": t_sharded / t_single})
            log(f"dataset shards: one process {t_single:.1f} s, {shards} shards "
                f"{t_sharded:.1f} s ({t_sharded / t_single:.2f}x)")
    return {"spec": spec["spec"], "shards": shards, "rounds": rounds,
            "goal_max_ratio": spec.get("max_ratio"),
            "command": f"skyrender dataset {spec['spec']} --out DIR [--shard I/{shards}]"}


def fit_exponent(points):
    """Least-squares slope of log(time) against log(pixels)."""
    if len(points) < 2:
        return None
    xs = [math.log(p) for p, _ in points]
    ys = [math.log(t) for _, t in points]
    mx, my = statistics.fmean(xs), statistics.fmean(ys)
    sxx = sum((x - mx) ** 2 for x in xs)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx if sxx > 0 else None


def scaling(cases, scenes):
    """Cases of one scene file (and overrides) and variant at several resolutions: the fitted
    exponent of time against pixels. Matrix scenes that differ only in frame counts (cumulus,
    cumulus_big) are one scene here."""
    groups = {}
    for c in cases:
        spec = scenes[c["scene"]]
        if spec.get("heading_deg_per_frame"):
            continue  # a pan's frames are not a still's
        name = next(n for n, s in scenes.items()
                    if s.get("scene") == spec.get("scene") and s.get("set") == spec.get("set")
                    and not s.get("heading_deg_per_frame"))
        groups.setdefault((name, c["variant"]), []).append(
            (c["pixels"], c["summary"]["frame_ms"]["median"]))
    out = []
    for (scene, variant), pts in sorted(groups.items()):
        if len({p for p, _ in pts}) >= 2:
            out.append({"scene": scene, "variant": variant, "points": sorted(pts),
                        "exponent": fit_exponent(pts)})
    return out


def write_csv(path, cases, comparisons):
    names = sorted({n for c in cases for f in c["frames"] for n in f["passes"]})
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["kind", "scene", "resolution", "variant", "build", "frame", "frame_ms",
                    "render_ms", "display_ms", "gpu_ms"] + [f"{n}_ms" for n in names])
        rows = [("case", c["scene"], c["resolution"], c["variant"], "a", c["frames"])
                for c in cases]
        for cmp in comparisons:
            for side in ("a", "b"):
                rows.append(("compare_" + side, cmp["scene"], cmp["resolution"],
                             cmp[side]["variant"], cmp[side]["build"], cmp[side]["frames"]))
        for kind, scene, res, variant, build, frames in rows:
            for f in frames:
                w.writerow([kind, scene, res, variant, build, f["frame"],
                            f"{f['frame_ms']:.3f}", f"{f['render_ms']:.3f}",
                            f"{f['display_ms']:.3f}", f"{f['gpu_ms']:.3f}"] +
                           [f"{f['passes'].get(n, 0.0):.3f}" for n in names])


def plot(out_dir, cases, fits, fmt):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    files = []
    if cases:
        names = []
        for c in cases:
            for n in c["summary"]["pass_median_ms"]:
                if n not in names:
                    names.append(n)
        # The costliest passes first, so the legend reads in order of what matters.
        names.sort(key=lambda n: -sum(c["summary"]["pass_median_ms"].get(n, 0.0) for c in cases))
        labels = [f"{c['scene']}\n{c['resolution']} {c['variant']}" for c in cases]
        fig, (ax, share) = plt.subplots(2, 1, figsize=(max(6, 0.9 * len(cases) + 3), 9),
                                        sharex=True)
        bottom = [0.0] * len(cases)
        shares = [0.0] * len(cases)
        totals = [max(sum(c["summary"]["pass_median_ms"].values()), 1e-9) for c in cases]
        cmap = plt.get_cmap("tab20")
        for i, n in enumerate(names):
            vals = [c["summary"]["pass_median_ms"].get(n, 0.0) for c in cases]
            ax.bar(range(len(cases)), vals, bottom=bottom, label=n, color=cmap(i % 20))
            part = [100.0 * v / t for v, t in zip(vals, totals)]
            share.bar(range(len(cases)), part, bottom=shares, color=cmap(i % 20))
            bottom = [b + v for b, v in zip(bottom, vals)]
            shares = [b + v for b, v in zip(shares, part)]
        ax.scatter(range(len(cases)), [c["summary"]["frame_ms"]["median"] for c in cases],
                   marker="_", s=300, color="black", label="whole frame (wall)", zorder=3)
        ax.set_yscale("log")
        ax.set_ylabel("median ms per frame (log)")
        ax.set_title("Per-pass cost (GPU timestamps, medians) and the whole frame")
        ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.0, 1.0))
        share.set_ylabel("share of the GPU time (%)")
        share.set_xticks(range(len(cases)))
        share.set_xticklabels(labels, rotation=60, ha="right", fontsize=7)
        fig.tight_layout()
        path = os.path.join(out_dir, f"passes.{fmt}")
        fig.savefig(path, dpi=110)
        plt.close(fig)
        files.append(path)
    if fits:
        fig, ax = plt.subplots(figsize=(7, 5))
        for f in fits:
            xs = [p for p, _ in f["points"]]
            ys = [t for _, t in f["points"]]
            line, = ax.plot(xs, ys, "o-", label=f"{f['scene']} {f['variant']}: "
                            f"exponent {f['exponent']:.2f}")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("pixels")
        ax.set_ylabel("median ms per frame (wall)")
        ax.set_title("Cost against pixel count (fitted power law)")
        ax.legend(fontsize=8)
        ax.grid(True, which="both", alpha=0.3)
        fig.tight_layout()
        path = os.path.join(out_dir, f"scaling.{fmt}")
        fig.savefig(path, dpi=110)
        plt.close(fig)
        files.append(path)
    return files


def shrink_images(folder, max_width):
    """Box-filters every PNG in `folder` wider than max_width down by a whole factor, so a
    run's images stay small enough to commit (--full-images keeps them as rendered)."""
    import matplotlib.image as mpimg
    import numpy as np
    for name in sorted(os.listdir(folder)):
        path = os.path.join(folder, name)
        if not name.endswith(".png"):
            continue
        img = mpimg.imread(path)
        k = -(-img.shape[1] // max_width)
        if k <= 1:
            continue
        h, w = img.shape[0] // k * k, img.shape[1] // k * k
        small = img[:h, :w].reshape(h // k, k, w // k, k, -1).mean(axis=(1, 3))
        mpimg.imsave(path, np.clip(small, 0.0, 1.0))


def git_build():
    def git(*args):
        try:
            return subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True,
                                  check=True).stdout.strip()
        except (subprocess.CalledProcessError, FileNotFoundError):
            return ""
    commit = git("rev-parse", "--short=12", "HEAD")
    dirty = bool(git("status", "--porcelain", "--untracked-files=no"))
    return commit + ("-dirty" if dirty and commit else "") or "unknown"


def goals(result):
    """The issue's goals, as ratios measured in this run (benchmarks/README.md)."""
    g = {}
    by = {(c["scene"], c["resolution"], c["variant"]): c for c in result["cases"]}
    spec = result["matrix"].get("goals", {})
    pan = spec.get("pan")
    if pan:
        c = by.get((pan["scene"], pan["resolution"], pan["variant"]))
        entry = {"case": f"{pan['scene']} {pan['resolution']} {pan['variant']}"}
        if c:
            entry["ours_median_ms"] = c["summary"]["frame_ms"]["median"]
            entry["psnr_db_min"] = min((q["psnr_db"] for q in c["quality"]), default=None)
        rounds = result.get("peer_rounds")
        if rounds:
            # Interleaved: each round's peer over ours, then their median.
            speedups = [r["speedup"] for r in rounds]
            entry["rounds"] = [{"peer_median_ms": r["peer_median_ms"],
                                "ours_median_ms": r["ours_median_ms"],
                                "speedup": r["speedup"]} for r in rounds]
            entry["speedup_over_peer"] = stats(speedups)
            if pan.get("min_speedup"):
                entry["goal"] = pan["min_speedup"]
                entry["met"] = statistics.median(speedups) >= pan["min_speedup"]
        if len(entry) > 1:
            g["pan_vs_peer"] = entry
    budget = spec.get("pass_budget")
    empties = result.get("empty_passes") or []
    if budget and empties:
        c = by.get((budget["scene"], budget["resolution"], budget["variant"]))
        if c:
            by_pixels = {e["pixels"]: e for e in empties}
            limit = budget.get("max_ratio", 2.0)
            passes, other = {}, {}
            for name, ms in c["summary"]["pass_median_ms"].items():
                if name in budget.get("exclude", []):
                    continue
                e = by_pixels.get(c["summary"]["pass_texels"].get(name))
                if not e:
                    other[name] = ms  # a LUT or a map: not a full-screen pass
                    continue
                ratio = ms / e["gpu_ms"]["median"]
                passes[name] = {"ms": ms, "resolution": e["resolution"],
                                "empty_ms": e["gpu_ms"]["median"], "ratio": ratio,
                                "met": ratio <= limit}
            g["passes_vs_empty"] = {
                "case": f"{budget['scene']} {budget['resolution']} {budget['variant']}",
                "max_ratio": limit, "excluded": budget.get("exclude", []), "passes": passes,
                "met": sum(p["met"] for p in passes.values()), "of": len(passes),
                "not_full_screen_ms": other}
    still = spec.get("still")
    if still:
        for cmp in result["comparisons"]:
            if (cmp["scene"], cmp["resolution"]) == (still["scene"], still["resolution"]) and \
                    cmp["a"]["build"] != cmp["b"]["build"]:
                # B is the baseline: its time over ours is how much faster we are.
                g["still_vs_baseline"] = {
                    "speedup": cmp["ratio_b_over_a"]["median"],
                    "baseline": cmp["b"]["build"]}
        c = by.get((still["scene"], still["resolution"], still["variant"]))
        if c and c["quality"]:
            g.setdefault("still_vs_baseline", {})["psnr_db"] = c["quality"][-1]["psnr_db"]
    for want in spec.get("cost_vs_noon", []):
        for cmp in result["comparisons"]:
            if (cmp["scene"], cmp["resolution"], cmp["a"]["variant"], cmp["b"]["variant"]) == \
                    (want["scene"], want["resolution"], want["a"], want["b"]) and \
                    cmp["a"]["build"] == cmp["b"]["build"]:
                ratio = cmp["ratio_b_over_a"]["median"]
                g.setdefault("cost_vs_noon", []).append(
                    {"case": f"{want['scene']} {want['resolution']}: {want['b']} over {want['a']}",
                     "ratio": ratio, "spread": [cmp["ratio_b_over_a"]["min"],
                                                cmp["ratio_b_over_a"]["max"]],
                     "goal": want.get("max_ratio"),
                     "met": want.get("max_ratio") is None or ratio <= want["max_ratio"]})
    views = spec.get("views_in_one_frame")
    if views:
        for cmp in result["comparisons"]:
            if (cmp["scene"], cmp["resolution"], cmp["a"]["variant"], cmp["b"]["variant"]) == \
                    (views["scene"], views["resolution"], views["a"], views["b"]) and \
                    cmp["a"]["build"] == cmp["b"]["build"]:
                # B (the views in one frame) over A (as many separate renders), interleaved.
                ratio = cmp["ratio_b_over_a"]["median"]
                g["views_in_one_frame"] = {
                    "case": f"{views['scene']} {views['resolution']}: {views['b']} over "
                            f"{views['a']}",
                    "ratio": ratio, "spread": [cmp["ratio_b_over_a"]["min"],
                                               cmp["ratio_b_over_a"]["max"]],
                    "goal": views.get("max_ratio"),
                    "met": views.get("max_ratio") is None or ratio <= views["max_ratio"]}
    first = result.get("first_frame")
    if first and first.get("goal_setup_ms"):
        warm = first["runs"][1:] or first["runs"]
        parts = {k: statistics.median(r["costs"][k] for r in warm)
                 for k in ("renderer_pipelines_ms", "pipelines_ms", "textures_ms",
                           "lut_bake_gpu_ms", "render_ms")}
        g["first_frame_setup"] = {
            "case": f"skyrender {first['scene']} {first['resolution']}, caches warm",
            "setup_ms": first["setup_ms_median"], "goal_ms": first["goal_setup_ms"],
            "met": first["setup_ms_median"] < first["goal_setup_ms"], "parts_ms": parts}
    for window in result.get("windows") or []:
        if window.get("goal_fps"):
            g.setdefault("window_pan_fps", []).append(
                {"fps": window["fps_after_first"], "goal": window["goal_fps"],
                 "met": window["fps_after_first"] >= window["goal_fps"],
                 "case": f"skyview {window['scene']} {window['resolution']} "
                         f"{' '.join(window['set']) or '(the scene as written)'}"})
    shards = result.get("dataset_shards")
    if shards and shards.get("goal_max_ratio"):
        ratio = statistics.median(r["ratio"] for r in shards["rounds"])
        g["dataset_shards"] = {
            "case": f"{shards['spec']}: {shards['shards']} shards at once and merged, over one "
                    "process, total wall time",
            "ratio": ratio, "spread": [min(r["ratio"] for r in shards["rounds"]),
                                       max(r["ratio"] for r in shards["rounds"])],
            "goal": shards["goal_max_ratio"], "met": ratio <= shards["goal_max_ratio"]}
    fits = [f for f in result["scaling"] if f["variant"] == spec.get("scaling_variant", "still")]
    if fits:
        g["scaling_exponents"] = {f["scene"]: f["exponent"] for f in fits}
    return g


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--matrix", default=os.path.join(ROOT, "benchmarks", "matrix.json"))
    ap.add_argument("--skybench", default=os.path.join(ROOT, "build", "release", "benchmarks",
                                                       "skybench"))
    ap.add_argument("--skyview", default=os.path.join(ROOT, "build", "release", "apps", "skyview",
                                                      "skyview"),
                    help="the window whose slow pan the matrix's 'window' entry times")
    ap.add_argument("--skyrender", default=os.path.join(ROOT, "build", "release", "apps",
                                                        "skyrender", "skyrender"),
                    help="the command line whose first frame the matrix's 'first_frame' entry "
                         "times")
    ap.add_argument("--baseline", help="a second build's skybench: the matrix's compare "
                    "entries run this build (A) against it (B), frame by frame")
    ap.add_argument("--out", help="results folder (default benchmarks/results/DATE_DEVICE)")
    ap.add_argument("--smoke", action="store_true", help="the tiny configuration CI runs")
    ap.add_argument("--compare", nargs=2, metavar=("A", "B"),
                    help="only alternate variants A and B of --scene at --resolution")
    ap.add_argument("--scene", default="peer_view")
    ap.add_argument("--resolution", default="640x360")
    ap.add_argument("--frames", type=int, help="measured frames per case (overrides the matrix)")
    ap.add_argument("--only", help="comma-separated scenes: run only these of the matrix")
    ap.add_argument("--peer", choices=["auto", "on", "off"], default="auto",
                    help="run takram three-clouds (../shared/peers/takram) at the goal's view; "
                         "auto: when the matrix asks and the peer is present")
    ap.add_argument("--plots", choices=["png", "svg", "off"], default="png")
    ap.add_argument("--full-images", action="store_true",
                    help="keep the images as rendered (default: shrunk to 640 px wide)")
    args = ap.parse_args()

    def log(msg):
        print(msg, file=sys.stderr, flush=True)

    try:
        with open(args.matrix) as fh:
            matrix = json.load(fh)
    except (OSError, json.JSONDecodeError) as e:
        raise HarnessError(f"{args.matrix}: {e}")
    if args.smoke:
        smoke = matrix["smoke"]
        matrix = smoke | {"scenes": matrix["scenes"], "variants": matrix["variants"]}
        for name, over in smoke.get("scene_overrides", {}).items():
            matrix["scenes"][name] = matrix["scenes"][name] | over
    if args.frames:
        matrix["frames"] = args.frames
        for s in matrix["scenes"].values():
            s.pop("frames", None)

    env = dict(os.environ, MESA_SHADER_CACHE_DISABLE="true")
    started = time.monotonic()
    workers = {"a": Worker(args.skybench, "a", env)}
    try:
        if args.baseline:
            workers["b"] = Worker(args.baseline, "b", env)
        stamp = datetime.datetime.now().strftime("%Y-%m-%d")
        device = re.sub(r"[^A-Za-z0-9]+", "-", workers["a"].device.split("(")[0]).strip("-")
        out_dir = args.out or os.path.join(ROOT, "benchmarks", "results", f"{stamp}_{device}")
        os.makedirs(os.path.join(out_dir, "images"), exist_ok=True)
        h = Harness(matrix, workers, out_dir, log)

        only = set(args.only.split(",")) if args.only else None
        if args.compare:
            h.compare(args.scene, args.resolution, *args.compare)
        else:
            for i, run in enumerate(matrix.get("runs", [])):
                # Each group of cases in a fresh skybench: a process that has made and freed
                # a dozen renderers (1080p transients, JIT code) runs later cases up to 30 %
                # slower, which would make a case's time depend on what ran before it.
                if i > 0:
                    h.restart("a")
                for scene in run["scenes"]:
                    if only and scene not in only:
                        continue
                    for res in run["resolutions"]:
                        for variant in run["variants"]:
                            h.run_case(scene, res, variant, run.get("quality", False))
            for cmp in matrix.get("compare", []):
                if only and cmp["scene"] not in only:
                    continue
                h.restart("a")
                if cmp.get("builds") and "b" not in workers:
                    log(f"compare {cmp['scene']}: needs --baseline; skipped")
                    continue
                if not cmp.get("builds") and "b" in workers:
                    saved = workers.pop("b")
                    h.compare(cmp["scene"], cmp["resolution"], cmp["a"], cmp["b"])
                    workers["b"] = saved
                else:
                    h.compare(cmp["scene"], cmp["resolution"], cmp["a"], cmp["b"])

        empties = []
        budget = matrix.get("goals", {}).get("pass_budget")
        if budget and not args.compare and (not only or budget["scene"] in only):
            # The yardstick at the budget case's size and at half of it (the clouds marched
            # at half resolution), in a fresh skybench like every group.
            h.restart("a")
            width, height = parse_resolution(budget["resolution"])
            for res in (budget["resolution"], f"{(width + 1) // 2}x{(height + 1) // 2}"):
                empties.append(h.empty_pass(res, budget.get("frames", 5)))

        peer, rounds = None, None
        want_peer = matrix.get("peer") and args.peer != "off" and not args.compare
        if want_peer or args.peer == "on":
            spec = matrix.get("peer") or {"resolution": "1280x720", "frames": 5}
            goal = matrix.get("goals", {}).get("pan")
            if goal:
                rounds = h.peer_rounds(spec, goal, spec.get("rounds", 3), log)
                peer = rounds[-1]["peer"] if rounds else None
            else:
                peer = run_peer(spec["resolution"], spec.get("frames", 5), log)
            if peer and peer.get("screenshot_path") and os.path.isfile(peer["screenshot_path"]):
                shutil.copy(peer["screenshot_path"],
                            os.path.join(out_dir, "images", "peer_" + spec["resolution"] + ".png"))

        first_frame = None
        if matrix.get("first_frame") and not args.compare and \
                (not only or "first_frame" in only):
            first_frame = run_first_frame(matrix["first_frame"], args.skyrender, log)

        dataset_shards = None
        if matrix.get("dataset_shards") and not args.compare and \
                (not only or "dataset_shards" in only):
            dataset_shards = run_dataset_shards(matrix["dataset_shards"], args.skyrender, log)

        windows = []
        specs = matrix.get("window") or []
        if isinstance(specs, dict):
            specs = [specs]
        if specs and not args.compare and (not only or "window" in only):
            for spec in specs:
                window = run_window(spec, args.skyview, env, log)
                if window:
                    windows.append(window)
        validation = h.validation_seen + [m for w in workers.values() for m in w.validation]
        for window in windows:
            validation += window["validation_messages"]
        result = {
            "date": datetime.datetime.now().isoformat(timespec="seconds"),
            "device": workers["a"].device, "build": git_build(),
            "version": workers["a"].version,
            "baseline": workers["b"].binary if "b" in workers else None,
            "host": {"machine": platform.machine(), "cpus": os.cpu_count(),
                     "python": platform.python_version()},
            "environment": {"MESA_SHADER_CACHE_DISABLE": "true"},
            "matrix": matrix, "cases": h.cases, "comparisons": h.comparisons,
            "scaling": scaling(h.cases, matrix["scenes"]), "peer": peer, "peer_rounds": rounds,
            "empty_passes": empties, "windows": windows, "first_frame": first_frame,
            "dataset_shards": dataset_shards,
            "validation_messages": validation,
            "harness_wall_s": time.monotonic() - started,
        }
        result["goals"] = goals(result)
        with open(os.path.join(out_dir, "results.json"), "w") as fh:
            json.dump(result, fh, indent=1)
        write_csv(os.path.join(out_dir, "results.csv"), h.cases, h.comparisons)
        if not args.full_images and args.plots != "off":
            shrink_images(os.path.join(out_dir, "images"), 640)
        plots = [] if args.plots == "off" else plot(out_dir, h.cases, result["scaling"],
                                                    args.plots)
        log(f"wrote {out_dir}/results.json, results.csv" +
            "".join(f", {os.path.basename(p)}" for p in plots) +
            f" in {result['harness_wall_s']:.0f} s")
        print(json.dumps({"out": out_dir, "goals": result["goals"],
                          "harness_wall_s": round(result["harness_wall_s"], 1)}))
        if validation:
            raise HarnessError(f"{len(validation)} Vulkan validation messages, the first: "
                               f"{validation[0]}")
    finally:
        for w in workers.values():
            w.close()
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except HarnessError as e:
        print(f"error: {e}", file=sys.stderr)
        sys.exit(2)
    except KeyboardInterrupt:
        sys.exit(130)

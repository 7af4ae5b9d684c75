#!/usr/bin/python3
"""The teaching page in a real browser: `ccdlab export CONFIG --html` then headless Chromium (Debian `chromium`).

usage: check_page.py CCDLAB CONFIG WORKDIR [--screenshots DIR]

Checks that the page opens from disk, draws the mesh (non-background pixels in the middle of the canvas, read
back by the page's own #selftest), that moving the step slider changes the picture, that the walk-through draws,
and that the page made no network request: none in the browser's net log with the page as initiator, no resource
in the page's own resource timing, no Content-Security-Policy refusal (the policy forbids every fetch). Screenshots of the
views docs/teaching.md shows are written to --screenshots (default: WORKDIR). Exit 0 when all hold; 77 (skipped)
when chromium is not installed.
"""
from __future__ import annotations

import argparse
import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

VIEWS = {  # screenshot name -> the page's address fragment
    "page_step": "step=5&depth=3",
    "page_bvh_k6": "step=5&depth=4&k=6&kept=0&sprouted=0&pruned=0&contacts=0",
    "page_bvh_k26": "step=5&depth=4&k=26&kept=0&sprouted=0&pruned=0&contacts=0",
    "page_front": "step=5&bvh=0&contacts=0&mesh=0",
    "page_contact": "step=5&bvh=0&kept=0&sprouted=0&pruned=0&contact=100",
    "page_walk": "mode=walk&walk=1&visit=30",
}


def chromium(args: list[str], url: str, log: Path | None = None, timeout: int = 120) -> subprocess.CompletedProcess:
    cmd = ["chromium", "--headless", "--no-sandbox", "--disable-gpu", "--enable-unsafe-swiftshader",
           "--use-angle=swiftshader", "--window-size=1280,800", "--hide-scrollbars", "--no-first-run",
           "--disable-background-networking", "--disable-component-update", "--disable-sync",
           "--disable-default-apps", "--enable-logging=stderr", "--v=0"]
    if log:
        cmd.append(f"--log-net-log={log}")
    return subprocess.run(cmd + args + [url], capture_output=True, text=True, timeout=timeout)


def page_requests(net_log: Path) -> list[str]:
    """Network URLs a page asked for, from the browser's net log: requests with an origin as initiator. (The
    browser's own services — update checks, the network clock — are initiated by "not an origin" and ignored.)"""
    if not net_log.exists():
        return ["no net log written"]
    try:
        events = json.loads(net_log.read_text(errors="replace")).get("events", [])
    except json.JSONDecodeError:  # a log cut short: read it as text, request by request
        events = [json.loads(m) for m in re.findall(r'\{"params":\{[^{}]*"url":"[^"]*"[^{}]*\}[^{}]*(?:\{[^{}]*\}[^{}]*)*\}', net_log.read_text(errors="replace"))]
    urls = set()
    for e in events:
        p = e.get("params", {})
        url, initiator = p.get("url", ""), p.get("initiator")
        if re.match(r"(https?|wss?|ftp)://", url) and initiator not in (None, "not an origin"):
            urls.add(f"{url} (initiator {initiator})")
    return sorted(urls)


def ink(png: Path) -> float:
    import matplotlib.image as mpimg
    img = mpimg.imread(str(png))
    h, w = img.shape[:2]
    centre = img[h // 4: 3 * h // 4, w // 8: 5 * w // 8, :3]  # the canvas is the left part, the panel the right
    return float(((centre < 0.96).any(axis=2)).mean())


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("ccdlab")
    parser.add_argument("config")
    parser.add_argument("workdir", type=Path)
    parser.add_argument("--screenshots", type=Path)
    args = parser.parse_args()
    if not shutil.which("chromium"):
        print("check_page.py: chromium not installed: skipped", file=sys.stderr)
        return 77
    args.workdir.mkdir(parents=True, exist_ok=True)
    shots = args.screenshots or args.workdir
    shots.mkdir(parents=True, exist_ok=True)
    page = args.workdir / "teaching.html"
    subprocess.run([args.ccdlab, "export", args.config, "--html", str(page), "--no-progress"], check=True)
    size = page.stat().st_size
    failures = []
    if size > 10e6:
        failures.append(f"the page is {size / 1e6:.1f} MB, over 10 MB")
    url = page.resolve().as_uri()

    # The page's self-test: pixels read back from its canvas, before and after moving the step slider.
    net = args.workdir / "net.json"
    r = chromium(["--dump-dom"], url + "#selftest", log=net)  # real time: the page measures its frame rate
    m = re.search(r'<pre id="selftest">([^<]*)</pre>', r.stdout)
    result = json.loads(m.group(1)) if m and m.group(1) else None
    if not result:
        failures.append("the self-test did not run: " + r.stderr[-800:])
    else:
        print(f"self-test: {result}")
        print(f"frames per second, software rendering in headless Chromium: {result['fps_software']:.0f}")
        if result["centre_ink"] < 0.05:
            failures.append(f"the mesh is not drawn: {result['centre_ink']:.3f} of the canvas centre is not background")
        if result["changed_by_step_slider"] < 0.002:
            failures.append(f"the step slider did not change the picture ({result['changed_by_step_slider']:.4f} of the pixels)")
        if result["step_after"] != result["steps"] - 1:
            failures.append(f"the step slider did not reach step {result['steps'] - 1}")
        if result["resources"] or result["csp_violations"]:
            failures.append(f"the page loaded {result['resources']} and was refused {result['csp_violations']}")
    if re.search(r"Refused to (load|connect)|Content.Security.Policy", r.stderr):
        failures.append("the page tried to fetch something: " + r.stderr[-800:])
    urls = page_requests(net)
    if urls:
        failures.append(f"network requests by the page: {urls[:5]}")

    # Screenshots of the views docs/teaching.md shows.
    for name, fragment in VIEWS.items():
        png = shots / f"{name}.png"
        chromium([f"--screenshot={png}", "--virtual-time-budget=20000"], f"{url}#{fragment}")
        if not png.exists():
            failures.append(f"no screenshot {png}")
            continue
        share = ink(png)
        print(f"{png}: {share:.2f} of the canvas centre drawn")
        if share < 0.03:
            failures.append(f"{png}: the canvas looks empty ({share:.3f})")

    print(f"{page}: {size / 1e6:.2f} MB")
    for f in failures:
        print("FAIL: " + f, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

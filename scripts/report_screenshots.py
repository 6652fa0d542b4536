#!/usr/bin/python3
"""Screenshots of the README: one PNG per kind of report figure, made by headless Chromium from reports.

usage: scripts/report_screenshots.py OUT_DIR KIND[#SKIP]=REPORT.html[:WIDTHxHEIGHT] ...
  KIND is a figure kind of the report (convergence, runs, ecdf, law, ...) or "loops" (the first record's three
  figures: force–displacement, force–velocity, residual); the shot shows the first row of such figures and
  nothing else, cropped to the window (default 1160x380); #SKIP skips that many rows of them. Example:
  scripts/report_screenshots.py docs/report loops=results/fvd/report.html convergence=results/fvd/report.html
"""
import os
import shutil
import subprocess
import sys

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")


def shot(out_png, report, css, width, height):
    with open(report) as f:
        page = f.read()
    page = page.replace('<div id="report"></div>', f"<style>{css}</style><div id=\"report\"></div>", 1)
    # Reports of more than 12 conditions draw a condition when it is opened: open them all.
    page = page.replace("</body>", "<script>document.querySelectorAll('details.condition')"
                        ".forEach(function (d) { d.open = true; });</script></body>", 1)
    tmp = out_png + ".html"
    with open(tmp, "w") as f:
        f.write(page)
    subprocess.run([CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
                    "--virtual-time-budget=60000", f"--window-size={width},{height}", f"--screenshot={out_png}",
                    "file://" + os.path.abspath(tmp)], check=True, capture_output=True)
    os.remove(tmp)
    print(out_png)


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    base = ("h1, nav, p, h2, table, details.table, div.errors { display: none !important; } "
            "body { margin: 8px; } details.condition > summary { display: none; } ")
    for arg in sys.argv[2:]:
        name, spec = arg.split("=", 1)
        name, _, skip = name.partition("#")  # runs#3: the 4th row of run-distribution figures
        skip = int(skip or 0)
        report, _, size = spec.partition(":")
        width, height = (int(v) for v in (size or "1160x380").split("x"))
        if name == "loops":  # the first condition's record: its three figures
            css = base + ("details.condition { display: none; } #loops ~ details.condition:first-of-type "
                          "{ display: block; } figure.fig:not([data-kind^=loop]):not([data-kind=residual]) "
                          "{ display: none; }")
            shot(os.path.join(out, "loops.png"), report, css, width, height)
            continue
        # Only figures of this kind; the window's height crops the page after the first row of them.
        css = base + (f"figure.fig:not([data-kind={name}]) {{ display: none; }} "
                      f"details.condition:not(:has(figure[data-kind={name}])) {{ display: none; }} "
                      f"div.row:not(:has(figure[data-kind={name}])) {{ display: none; }} "
                      f"div.row:has(figure[data-kind={name}]) ~ div.row {{ display: none; }} "
                      f"details.condition:has(figure[data-kind={name}]) ~ details.condition {{ display: none; }}")
        if skip:
            row = f"div.row:has(figure[data-kind={name}])"
            before = " ~ ".join([row] * (skip + 1))
            css += f" {row}:not({before}) {{ display: none; }} {before} {{ display: block; }}"
            css += f" {before} ~ {row} {{ display: none; }} {before} {{ display: flex; }}"
        shot(os.path.join(out, f"{name}.png"), report, css, width, height)


if __name__ == "__main__":
    main()

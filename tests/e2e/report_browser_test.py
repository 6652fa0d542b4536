#!/usr/bin/python3
"""The HTML report in a real browser.

Runs a small sweep (Bingham per current with PSO and DE, Bouc-Wen per current, a current-dependent Bingham law
fitted at 0 and 1 A predicting 0.5 A, a regression of f_c on I) on records made by `dampbench simulate` with
known parameters, writes `dampbench report`, renders it in headless Chromium and checks:
  - no message on the browser console (the page logs nothing unless something fails) and no drawing error;
  - every figure the data calls for is present and drawn: a loop has a path with one vertex per drawn sample
    for the measured force and for each model, every other figure has at least one drawn path or point;
  - the fixed-target runtime section holds, under the ECDFs, the runtime tables with the cells of
    `dampbench table --kind runtime` (its rows and columns: success, ERT and ERT in seconds per optimizer);
  - the loops' model forces equal `dampbench simulate` of the best run's parameters read from the SQLite store
    (not from the report), at the drawn samples;
  - an empty store, a file that is not a store and a missing store are refused with a message and leave no file;
  - a report of 13 conditions starts with them collapsed (only the run distribution drawn) and draws each
    condition's loops and convergence curve when it is opened;
  - a `fit --report` with held-out folds and --predict (datasets/fvd records) draws, in its held-out section, the
    loops of each held-out record (measured and predicted, one vertex per sample) titled with its fold, and a
    `fit --report` without held-out options has no such section;
  - a run distribution whose runs agree to 1e-12 reads "all runs equal" with one short tick label, and one whose
    runs agree to 1e-5 is drawn relative to the best run with short tick labels (no 12-digit labels).

usage: report_browser_test.py DAMPBENCH WORK_DIR
Exit 77 (ctest: skipped) when Chromium is not installed; scripts/install-deps.sh installs it, so CI runs it.
"""
import html.parser
import json
import os
import shutil
import sqlite3
import struct
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import store_test_support as support  # noqa: E402

DAMPBENCH, WORK = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
failures = []


def check(ok, message):
    if not ok:
        failures.append(message)
        print("FAIL:", message)


def run(*args, ok=True):
    p = subprocess.run([DAMPBENCH, *args], cwd=WORK, capture_output=True, text=True)
    if ok and p.returncode != 0:
        sys.exit(f"dampbench {' '.join(args)} failed ({p.returncode}):\n{p.stdout}\n{p.stderr}")
    return p


SWEEP = support.current_sweep("report-test", 4, extra='\n[[tables]]\nkind = "runs"\n')


def make_sweep():
    shutil.rmtree(WORK, ignore_errors=True)
    os.makedirs(WORK)
    support.write_current_records(DAMPBENCH, WORK)
    with open(os.path.join(WORK, "sweep.toml"), "w") as f:
        f.write(SWEEP)
    run("run", os.path.join(WORK, "sweep.toml"), "-o", "out", "--quiet")
    run("report", "out/store.sqlite", "-o", "report.html")


class Dom(html.parser.HTMLParser):
    """Figures (data-kind, drawn paths with their d, points), the body's data-rendered, the error box, the data."""

    def __init__(self):
        super().__init__()
        self.figures, self.rendered, self.errors_shown, self.data_text = [], None, False, None
        self._depth, self._in_data, self._in_errors, self._errors_text = 0, False, False, ""
        self._axis_depth, self._text = 0, None
        self.section, self.sections = None, []
        self.tables = []  # {"id", "section"} of every drawn table

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "body":
            self.rendered = a.get("data-rendered")
        if tag == "h2":
            self.section = a.get("id")
            self.sections.append(self.section)
        if tag == "table" and a.get("data-id"):
            self.tables.append({"id": a.get("data-id"), "section": self.section})
        if tag == "figure":
            self.figures.append({"kind": a.get("data-kind"), "paths": [], "points": 0, "ticks": [], "texts": [],
                                 "section": self.section})
        if self.figures and tag == "path" and "series" in (a.get("class") or ""):
            self.figures[-1]["paths"].append(a.get("d") or "")
        if self.figures and tag == "circle" and "point" in (a.get("class") or ""):
            self.figures[-1]["points"] += 1
        if tag == "script" and a.get("id") == "dampbench-data":
            self._in_data = True
        if tag == "g" and self.figures:
            self._axis_depth = self._axis_depth + 1 if self._axis_depth or "axis" in (a.get("class") or "") else 0
        if tag in ("text", "figcaption") and self.figures:
            self._text = {"tick": bool(self._axis_depth), "text": ""}
        if tag == "div" and a.get("id") == "report-errors":
            self.errors_shown = "none" not in (a.get("style") or "")
            self._in_errors = True

    def handle_endtag(self, tag):
        if tag == "script":
            self._in_data = False
        if tag == "g" and self._axis_depth:
            self._axis_depth -= 1
        if tag in ("text", "figcaption") and self._text is not None:
            self.figures[-1]["ticks" if self._text["tick"] else "texts"].append(self._text["text"])
            self._text = None
        if tag == "div":
            self._in_errors = False

    def handle_data(self, text):
        if self._text is not None:
            self._text["text"] += text
        if self._in_data:
            self.data_text = (self.data_text or "") + text
        if self._in_errors:
            self._errors_text += text


def vertices(d):
    """Vertices of an SVG path drawn by d3.svg.line: one M, L, H or V command each."""
    return sum(d.count(c) for c in "MLHV")


def stored_best_params():
    """(split, condition, model) → SI parameters of the lowest best_value run over optimizers, from the store."""
    db = sqlite3.connect(os.path.join(WORK, "out", "store.sqlite"))
    names = {m: n for m, n in db.execute("SELECT model, name FROM models WHERE part = 0")}
    splits = {s: n for s, n in db.execute("SELECT split, name FROM splits WHERE part = 0")}
    labels = {(s, f): l for s, f, l in db.execute("SELECT split, fitset, label FROM fitsets WHERE part = 0")}
    best = {}
    query = ("SELECT g.split, g.fitset, g.model, r.best_value, r.params FROM groups g JOIN runs r ON r.grp = g.grp "
             "WHERE g.part = 0 ORDER BY g.grp, r.run")
    for split, fitset, model, value, blob in db.execute(query):
        key = (splits[split], labels[(split, fitset)], names[model])
        params = list(struct.unpack(f"<{len(blob) // 8}d", blob))
        if key not in best or value < best[key][0]:
            best[key] = (value, params)
    return {k: v[1] for k, v in best.items()}


def simulated_force(model_entry, record_name, params):
    """F of `dampbench simulate` on the record with these parameters (full precision CSV)."""
    models = {"mrd.bingham": ("mrd.bingham", ""), "mrd.bouc_wen": ("mrd.bouc_wen", ""),
              "bingham(I)": ("mrd.bingham", "f_c=poly(I,1)")}
    model_id, laws = models[model_entry]
    names = json.loads(run("models", "--format", "json").stdout)["models"][model_id]["parameters"]
    names = [p["name"] for p in names]
    if laws:
        names = ["f_c_I0", "f_c_I1"] + [n for n in names if n != "f_c"]
    assert len(names) == len(params), (model_entry, names, params)
    args = ["simulate", "--model", model_id, "--params", ",".join(f"{n}={v!r}" for n, v in zip(names, params)),
            "--input", f"{record_name}.csv", "-o", "sim.csv"]
    if laws:
        args += ["--laws", laws]
    run(*args)
    with open(os.path.join(WORK, "sim.csv")) as f:
        rows = f.read().split("\n")[1:]
    return [float(r.split(",")[4]) for r in rows if r]


def render(report):
    """The DOM after the page's scripts ran, and the browser's console lines."""
    p = subprocess.run([CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--enable-logging=stderr", "--v=0",
                        "--user-data-dir=" + os.path.join(WORK, "chromium-profile"), "--virtual-time-budget=60000",
                        "--dump-dom", "file://" + report],
                       capture_output=True, text=True, timeout=300)
    check(p.returncode == 0, f"chromium exit {p.returncode}: {p.stderr[-2000:]}")
    console = [line for line in p.stderr.splitlines() if "CONSOLE" in line or "Uncaught" in line]
    check(not console, "browser console messages: " + " | ".join(console))
    dom = Dom()
    dom.feed(p.stdout)
    check(not dom.errors_shown, "the page shows drawing errors: " + dom._errors_text)
    return dom


def check_collapsed_conditions():
    """A report of more than 12 conditions starts collapsed and draws a condition when it is opened."""
    files = []
    for k in range(13):
        name = f"many_{k}.csv"
        run("simulate", "--model", "mrd.bingham", "--params", f"f_c={200 + 50 * k},c0=2000,f0=10", "--sine",
            "amp=0.01,freq=1,cycles=1,fs=100", "--noise-rel", "0.02", "--seed", str(k + 1), "-o", name)
        files.append(name)
    with open(os.path.join(WORK, "many.toml"), "w") as f:
        f.write('name = "many"\nruns = 2\nmodels = ["mrd.bingham"]\n[optimizer]\nname = "pso"\npopulation = 8\n'
                'iterations = 5\n[[datasets]]\nname = "m"\nfiles = ' + json.dumps(files) + "\n")
    run("run", os.path.join(WORK, "many.toml"), "-o", "many", "--quiet", "--no-report")
    run("report", "many/store.sqlite", "-o", "many.html")
    kinds = lambda dom: sorted({f["kind"] for f in dom.figures})
    closed = render(os.path.join(WORK, "many.html"))
    check(kinds(closed) == ["runs"], f"collapsed report draws {kinds(closed)}, expected only the run distribution")
    with open(os.path.join(WORK, "many.html")) as f:
        page = f.read()
    with open(os.path.join(WORK, "many_open.html"), "w") as f:
        f.write(page.replace("</body>", "<script>document.querySelectorAll('details.condition')"
                             ".forEach(function (d) { d.open = true; });</script></body>", 1))
    opened = render(os.path.join(WORK, "many_open.html"))
    count = {k: sum(1 for f in opened.figures if f["kind"] == k) for k in kinds(opened)}
    check(count == {"loop-displacement": 13, "loop-velocity": 13, "residual": 13, "convergence": 13, "runs": 1},
          f"opened conditions drew {count}")
    check(opened.rendered == str(len(opened.figures)), f"data-rendered={opened.rendered}, figures {len(opened.figures)}")
    for i, f in enumerate(opened.figures):
        check(sum(1 for d in f["paths"] if vertices(d) >= 2) + f["points"] > 0, f"opened figure {i} ({f['kind']}) is empty")


def check_fit_held_out():
    """`fit --report` with folds and --predict: one group per fold in the held-out section, each held-out record's
    loops drawn (measured and predicted) and titled with its fold; without held-out options, no such section."""
    fvd = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "datasets", "fvd")
    files = [os.path.join(fvd, n) for n in ("test1_20mm_92mms.csv", "test2_20mm_230mms.csv", "test3_20mm_460mms.csv")]
    fit = ["fit", "--model", "fvd.linear_viscous", "--runs", "2", "--pop", "8", "--iters", "5"]
    for f in files:
        fit += ["--data", f]
    run(*fit, "--folds", "leave-setting", "--predict", os.path.join(fvd, "test4_17mm_460mms.csv"),
        "--report", "held_out.html")
    dom = render(os.path.join(WORK, "held_out.html"))
    data = json.loads(dom.data_text)
    held = [(g["fold"], r) for g in data["held_out"] for r in g["records"]]
    check(len(held) == 4, f"held-out section has {len(held)} records, expected 4 (3 folds and --predict)")
    for kind in ("loop-displacement", "loop-velocity", "residual"):
        figs = [f for f in dom.figures if f["section"] == "held-out" and f["kind"] == kind]
        check(len(figs) == len(held), f"held-out section: {len(figs)} {kind} figures for {len(held)} held-out records")
    loops = [f for f in dom.figures if f["section"] == "held-out" and f["kind"] == "loop-displacement"]
    for (fold, r), fig in zip(held, loops):
        rec = data["records"][r["record"]]
        caption = fig["texts"][0] if fig["texts"] else ""
        check(caption.startswith(f"{rec['name']} held out by fold {fold}: "), f"held-out loop caption {caption!r}")
        check(len(fig["paths"]) == 2 and all(vertices(d) == len(rec["F"]) for d in fig["paths"]),
              f"held-out loop of {rec['name']}: vertices {[vertices(d) for d in fig['paths']]}, expected 2 × {len(rec['F'])}")
    check(dom.rendered == str(len(dom.figures)), f"held-out report: data-rendered={dom.rendered}, figures {len(dom.figures)}")
    run(*fit, "--report", "plain.html")
    plain = render(os.path.join(WORK, "plain.html"))
    check("held-out" not in plain.sections and not json.loads(plain.data_text)["held_out"],
          f"a fit without held-out options has a held-out section: {plain.sections}")
    check(plain.sections[:2] == ["loops", "convergence"], f"plain fit report sections {plain.sections}")


def check_run_axis():
    """Runs that agree to 1e-12 read as "all runs equal"; runs that agree to 1e-5 are drawn relative to the best.
    The page of the test sweep is drawn again with its run distributions replaced by such runs."""
    with open(os.path.join(WORK, "report.html")) as f:
        page = f.read()
    start = page.index('id="dampbench-data">') + len('id="dampbench-data">')
    end = page.index("</script>", start)
    data = json.loads(page[start:end])
    best = 0.0123456789012345
    equal = [[[best * (1 + k * 1e-12) for k in (0, 1, 2, -1)]]]
    close = [[[best * (1 + k * 1e-5) for k in (0, 1, 2, 3)]]]
    data["distributions"] = [
        {"part": "", "split": "", "model": m, "metric": "of_abs", "conditions": ["5mm3Hz0x5A"], "optimizers": ["pso"],
         "values": v} for m, v in (("equal", equal), ("close", close))]
    text = json.dumps(data).replace("</", "<\\/")
    with open(os.path.join(WORK, "run_axis.html"), "w") as f:
        f.write(page[:start] + text + page[end:])
    dom = render(os.path.join(WORK, "run_axis.html"))
    runs = [f for f in dom.figures if f["kind"] == "runs"]
    check(len(runs) == 2, f"{len(runs)} run distributions drawn, expected 2")
    if len(runs) != 2:
        return
    for fig, name in zip(runs, ("equal", "close")):
        # Tick labels of both axes: the condition name and the metric axis's labels.
        labels = [t for t in fig["ticks"] if t != "5mm3Hz0x5A"]
        check(labels and all(len(t) <= 8 for t in labels), f"{name} runs: tick labels {labels}, expected a few short ones")
        check(fig["points"] == 4, f"{name} runs: {fig['points']} points drawn, expected 4")
    check(len([t for t in runs[0]["ticks"] if t != "5mm3Hz0x5A"]) == 1, f"equal runs: ticks {runs[0]['ticks']}, expected one")
    check(any("all 4 runs equal" in t for t in runs[0]["texts"]), f"equal runs: no 'all 4 runs equal' in {runs[0]['texts']}")
    check(any("best − 1" in t for t in runs[1]["texts"]), f"close runs: the axis does not say 'best − 1': {runs[1]['texts']}")
    check(not any("all 4 runs equal" in t for t in runs[1]["texts"]), "close runs read as equal")


def main():
    if not CHROMIUM:
        print("SKIP: chromium is not installed (bash scripts/install-deps.sh installs it)")
        return 77
    make_sweep()
    dom = render(os.path.join(WORK, "report.html"))
    data = json.loads(dom.data_text)

    # Figures the data calls for: per condition 3 per drawn record, one convergence figure per model; one run
    # distribution per (split, model); ECDFs where a split compares optimizers; one per law.
    expected = {"loop-displacement": 0, "loop-velocity": 0, "residual": 0, "convergence": 0}
    for c in data["conditions"]:
        for r in c["records"]:
            for kind in ("loop-displacement", "loop-velocity", "residual"):
                expected[kind] += 1
        expected["convergence"] += len(c["convergence"])
    expected["runs"] = len(data["distributions"])
    expected["ecdf"] = len(data["ecdfs"])
    expected["law"] = len(data["laws"])
    got = {}
    for f in dom.figures:
        got[f["kind"]] = got.get(f["kind"], 0) + 1
    check(got == expected, f"figures drawn {got}, expected {expected}")
    check(expected["ecdf"] >= 1 and expected["law"] >= 1 and expected["loop-displacement"] == 3 + 3,
          f"the test sweep should give ECDF, law and 6 loop figures: {expected}")
    check(dom.rendered == str(len(dom.figures)), f"body data-rendered={dom.rendered}, figures {len(dom.figures)}")
    for i, f in enumerate(dom.figures):
        drawn = sum(1 for d in f["paths"] if vertices(d) >= 2) + f["points"]
        check(drawn > 0, f"figure {i} ({f['kind']}) is empty")

    # Runtime tables under the ECDFs: one per ECDF, drawn in that section, the cells `dampbench table` prints.
    runtimes = data["runtimes"]
    check(len(runtimes) == len(data["ecdfs"]), f"{len(runtimes)} runtime tables for {len(data['ecdfs'])} ECDFs")
    drawn = [t["id"] for t in dom.tables if t["section"] == "ecdf"]
    check(drawn == [t["id"] for t in runtimes], f"runtime tables drawn in the ECDF section: {drawn}")
    printed = json.loads(run("table", "out/store.sqlite", "--kind", "runtime", "--format", "json").stdout)["tables"]
    for t in runtimes:
        same = [p for p in printed if p["id"] == t["id"]]
        check(len(same) == 1 and same[0]["columns"] == t["columns"], f"runtime table {t['id']}: columns {t['columns']}")
        check("pso ERT s" in t["columns"] and "de ERT s" in t["columns"], f"no seconds columns in {t['columns']}")
        if same:
            conditions = [row[0] for row in same[0]["rows"]]
            check(conditions == [row[0] for row in t["rows"]], f"runtime table {t['id']}: rows {t['rows']}, printed {conditions}")
            ratios = [row[3] for row in same[0]["rows"]]  # pso's share of runs at the target, as a number
            check(all(isinstance(x, (int, float)) and 0 <= x <= 1 for x in ratios), f"pso success shares {ratios}")

    # Loops: one path per series with a vertex per drawn sample.
    loops = [f for f in dom.figures if f["kind"] == "loop-displacement"]
    k = 0
    for c in data["conditions"]:
        for r in c["records"]:
            rec = data["records"][r["record"]]
            n = len(rec["F"])
            paths = loops[k]["paths"]
            k += 1
            check(len(paths) == 1 + len(r["models"]), f"{c['condition']}: {len(paths)} paths for {len(r['models'])} models")
            check(all(vertices(d) == n for d in paths), f"{c['condition']}/{rec['name']}: vertices "
                  f"{[vertices(d) for d in paths]}, expected {n} each")

    # Loop data = simulate of the stored best parameters.
    stored = stored_best_params()
    compared = 0
    for c in data["conditions"]:
        for r in c["records"]:
            rec = data["records"][r["record"]]
            for m in r["models"]:
                params = stored[(c["split"], c["condition"], m["model"])]
                check(m["params"] == params, f"{m['model']} on {c['condition']}: report params {m['params']} != store {params}")
                force = simulated_force(m["model"], rec["name"], params)
                drawn = force[::rec["stride"]]
                scale = max(abs(x) for x in force)
                worst = max(abs(a - b) for a, b in zip(drawn, m["F"]))
                check(len(drawn) == len(m["F"]) and worst <= 1e-12 * scale,
                      f"{m['model']} on {rec['name']} ({c['condition']}): report force differs from simulate by {worst}")
                compared += 1
    check(compared == 3 * 2 + 3, f"compared {compared} (record, model) loops, expected 9")
    print(f"{len(dom.figures)} figures drawn, {compared} loops equal to simulate")

    # Refused stores: clear message, non-zero exit, no file written.
    open(os.path.join(WORK, "not_a_store.sqlite"), "w").write("hello")
    sqlite3.connect(os.path.join(WORK, "foreign.sqlite")).execute("CREATE TABLE t(x)")
    run("run", os.path.join(WORK, "sweep.toml"), "-o", "empty", "--quiet")
    db = sqlite3.connect(os.path.join(WORK, "empty", "store.sqlite"))
    db.execute("DELETE FROM runs")
    db.execute("DELETE FROM groups")
    db.commit()
    db.close()
    for store, words in (("missing.sqlite", "missing"), ("not_a_store.sqlite", "not"), ("foreign.sqlite", "not"),
                         ("empty/store.sqlite", "no finished task group")):
        out = os.path.join(WORK, "refused.html")
        p = run("report", store, "-o", out, ok=False)
        check(p.returncode != 0 and "dampbench: error:" in p.stderr and words in p.stderr,
              f"report {store}: exit {p.returncode}, stderr {p.stderr!r}")
        check(not os.path.exists(out), f"report {store} left {out}")
    check_collapsed_conditions()
    check_fit_held_out()
    check_run_axis()
    if failures:
        print(f"{len(failures)} failures")
        return 1
    print("OK")
    return 0


if __name__ == "__main__":
    sys.exit(main())

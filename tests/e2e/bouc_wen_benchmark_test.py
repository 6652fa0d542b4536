"""The hysteretic Bouc-Wen benchmark end to end through the dampbench executable.

- `datasets bouc-wen-benchmark`: the same seed gives the same files, another seed other ones.
- System records at the command line: a record mixing x and u is refused (exit 3), a rig model on a t,y,u record
  is refused naming both kinds (exit 2); `evaluate --periodic` scores the official test set as one steady period,
  far closer than the same record simulated from rest; `simulate` writes a record that loads again and scores 0.
- The preset datasets/presets/bouc_wen_benchmark.toml with a small budget (population 8, 2 iterations, 2 runs):
  run with --threads 1 and with --threads 2, its model files are identical byte for byte; the fit read the
  generated training record alone (never the test set); the saved model simulates the official multisine test set
  and the tool's own sine sweep to e_RMS <= 1e-6 m, with every parameter within 1 % of the benchmark's Table 1.
  Two runs are the fewest that get there with seed 1: one run ends in a local minimum (e_RMS 6.3e-4 m), two end at
  the best three find, bit for bit, and two runs still step in lockstep across the threads.

usage: bouc_wen_benchmark_test.py DAMPBENCH SOURCE_DIR WORK_DIR SHARED_DATA_DIR
Exit 77 (ctest: skipped) when the shared data (the official test set) are absent.
"""
import filecmp
import json
import os
import re
import shutil
import subprocess
import sys

DAMPBENCH, SOURCE, WORK, SHARED = (os.path.abspath(a) for a in sys.argv[1:5])
TEST_SET = os.path.join(SHARED, "bouc-wen-benchmark", "validation_multisine.csv")
TRUTH = "m=2,c=10,k=5e4,alpha=5e4,beta_gamma=800,beta_delta=-1100,nu=1"
TABLE1 = {"m": 2, "c": 10, "k": 5e4, "alpha": 5e4, "beta_gamma": 800, "beta_delta": -1100, "nu": 1}
failures = []


def check(ok, message):
    if not ok:
        failures.append(message)
        print("FAIL:", message, flush=True)


def run(*args, code=0):
    p = subprocess.run([DAMPBENCH, *args], cwd=WORK, capture_output=True, text=True, timeout=900)
    if p.returncode != code:
        sys.exit(f"dampbench {' '.join(args)}: exit {p.returncode}, expected {code}:\n{p.stdout}\n{p.stderr}")
    return p


def rmse(*args):
    return json.loads(run("evaluate", *args, "--format", "json").stdout)[args[args.index("--data") + 1]]["rmse"]


def datasets():
    run("datasets", "bouc-wen-benchmark", "--seed", "3", "--into", "a")
    run("datasets", "bouc-wen-benchmark", "--seed", "3", "--into", "b")
    run("datasets", "bouc-wen-benchmark", "--seed", "4", "--into", "b")
    check(filecmp.cmp("a/training_seed3.csv", "b/training_seed3.csv", shallow=False), "seed 3 twice: files differ")
    with open("b/training_seed3.csv") as f3, open("b/training_seed4.csv") as f4:
        check(f3.read().splitlines()[5:] != f4.read().splitlines()[5:], "seeds 3 and 4 gave the same record")


def system_records():
    with open("mixed.csv", "w") as f:
        f.write("t,x,u\n" + "".join(f"{k},0,{k % 3}\n" for k in range(10)))
    p = run("evaluate", "--model", "sys.bouc_wen", "--params", TRUTH, "--data", "mixed.csv", code=3)
    check("column 'x' with a force input u" in p.stderr, f"mixed record message: {p.stderr}")
    p = run("evaluate", "--model", "fvd.linear_viscous", "--params", "m=1,C=1", "--data", "a/training_seed3.csv", code=2)
    check("is a system (t, y, u) record and model fvd.linear_viscous a rig model" in p.stderr, f"rig model: {p.stderr}")
    periodic = rmse("--model", "sys.bouc_wen", "--params", TRUTH, "--data", TEST_SET, "--periodic")
    from_rest = rmse("--model", "sys.bouc_wen", "--params", TRUTH, "--data", TEST_SET)
    print(f"Table 1 on the test set: e_RMS {periodic:.3g} m as one steady period, {from_rest:.3g} m from rest")
    check(periodic < 5e-7, f"true structure on the test set, --periodic: e_RMS {periodic} m, expected < 5e-7")
    check(from_rest > 20 * periodic, f"from rest ({from_rest}) should miss the steady test output by far more")
    # simulate writes a system record that loads again and scores exactly 0 against the same model; --states adds
    # the structure's velocity, acceleration and hysteretic force.
    run("simulate", "--model", "sys.bouc_wen", "--params", TRUTH, "--input", TEST_SET, "-o", "simulated.csv")
    again = rmse("--model", "sys.bouc_wen", "--params", TRUTH, "--data", "simulated.csv")
    check(again == 0, f"a simulated record scored against its own model: e_RMS {again}, expected 0")
    states = run("simulate", "--model", "sys.bouc_wen", "--params", TRUTH, "--input", TEST_SET, "--states").stdout
    check(states.splitlines()[0] == "t,y,u,v,a,z", f"simulate --states header: {states.splitlines()[0]}")


def preset():
    with open(os.path.join(SOURCE, "datasets", "presets", "bouc_wen_benchmark.toml")) as f:
        text = f.read()
    text = text.replace("@shared/", SHARED + "/")
    text = re.sub(r"(?m)^seed = 1$", "seed = 1\npopulation = 8\niterations = 2\nruns = 2", text)
    with open("small.toml", "w") as f:
        f.write(text)
    run("--threads", "1", "run", "small.toml", "-o", "out")
    shutil.copy("out/model_seed1.json", "model_1thread.json")
    run("--threads", "2", "run", "small.toml", "-o", "out")
    check(filecmp.cmp("out/model_seed1.json", "model_1thread.json", shallow=False), "model files differ: 1 vs 2 threads")
    with open("out/fit_seed1.json") as f:
        fit = json.load(f)
    check(json.dumps(fit["data"]).count("training_seed1.csv") == 1 and "validation" not in json.dumps(fit),
          f"the fit read more than the training record: {fit['data']}")
    with open("out/results.json") as f:
        result = json.load(f)["1"]
    print(f"preset (small budget): test e_RMS {result['test_e_rms_m']:.3g} m, sweep {result['sweep_e_rms_m']:.3g} m")
    check(result["test_e_rms_m"] <= 1e-6, f"test e_RMS {result['test_e_rms_m']} m > 1e-6")
    check(result["sweep_e_rms_m"] <= 1e-6, f"sweep e_RMS {result['sweep_e_rms_m']} m > 1e-6")
    for name, value in TABLE1.items():
        fitted = result["best_params"][name]
        check(abs(fitted - value) <= 0.01 * abs(value), f"{name} = {fitted}, Table 1 {value}: more than 1 % off")


def main():
    if not os.path.exists(TEST_SET):
        print(f"skipped: the benchmark's test set is absent ({TEST_SET}); CI has it beside the repository")
        sys.exit(77)
    shutil.rmtree(WORK, ignore_errors=True)
    os.makedirs(WORK)
    os.chdir(WORK)
    datasets()
    system_records()
    preset()
    if failures:
        sys.exit(f"{len(failures)} failure(s)")
    print("ok")


if __name__ == "__main__":
    main()

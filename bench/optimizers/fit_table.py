#!/usr/bin/python3
"""Every optimizer on the damper problems with no budget option (the automatic budget), then a Markdown table: per
(problem, optimizer) whether the runs converged or stopped at the cap, the best run's value over the best known,
the rounds and the wall seconds (docs/performance.md, "The automatic budget").

    bench/optimizers/fit_table.py [PROBLEMS [OPTIMIZERS]]      one `dampbench fit` per cell; comma-separated
                                                              subsets, default: all
    bench/optimizers/fit_table.py --store STORE [PROBLEMS [OPTIMIZERS]]
                                                              the same table from the store of
                                                              bench/optimizers/run.sh (its groups with the
                                                              automatic budget; 10 runs on the algebraic problems,
                                                              4 on the ODE ones, as its sweep files say)

Best known = the lowest best of any cell and of reference fits at 10 x the budget (fits: de and cmaes at 50 x 1000
x 10 runs on the algebraic problems, ga-lm at 24 x 300 x 4 on the ODE ones; a store: its -x10 entries).
Environment: DAMPBENCH (default build/dampbench), DAMPBENCH_SHARED_DATA_DIR (default ../shared/data), OUT (default
bench/optimizers/results/fit_table). A benchmark: the ODE rows take about an hour on 2 cores.
"""
import json
import math
import os
import re
import sqlite3
import subprocess
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
D = os.environ.get('DAMPBENCH', os.path.join(REPO, 'build', 'dampbench'))
SHARED = os.environ.get('DAMPBENCH_SHARED_DATA_DIR', os.path.join(REPO, '..', 'shared', 'data'))
OUT = os.environ.get('OUT', os.path.join(REPO, 'bench', 'optimizers', 'results', 'fit_table'))
UTFSM = ['--columns', 't,x,v,F', '--units', 'x=mm,v=mm/s', '--conditions', 'utfsm', '--metric', 'nrmse']
FVD = ['test1_20mm_92mms', 'test2_20mm_230mms', 'test3_20mm_460mms', 'test4_17mm_460mms']
UTFSM_FILES = ['10mm1Hz1A', '5mm3Hz0x5A', '25mm0x25Hz0A']


def problems(kwok):
    p = {'kwok': ['--model', 'crfd.kwok', '--data', kwok, '--metric', 'rmse']}
    for i, f in enumerate(FVD, 1):
        p[f'fvd{i}'] = ['--model', 'fvd.gv_linear_elastic', '--data', os.path.join(REPO, 'datasets', 'fvd', f + '.csv'),
                        '--bounds', 'alpha=0.1:1,K1=0:2e7']
    for m in ['mrd.spencer', 'mrd.bouc_wen']:
        for f in UTFSM_FILES:
            p[f'{m.split(".")[1]}_{f}'] = ['--model', m, '--data', os.path.join(SHARED, 'utfsm-mr-damper', f + '.txt')] + UTFSM
    return p


OPTIMIZERS = {'pso': ['pso'], 'ga': ['ga'], 'aga': ['aga'], 'de': ['de'], 'cmaes': ['cmaes'],
              'cmaes-bipop': ['cmaes', 'restarts=bipop'], 'ga-lm': ['ga-lm'], 'ga-sqp': ['ga-sqp'],
              'ga-lm+cmaes': ['ga-lm', 'global=cmaes'], 'ga-sqp+cmaes': ['ga-sqp', 'global=cmaes']}


def write_kwok(path):
    """The noisy Kwok record of the tests (bench/optimizers/run.sh writes the same one)."""
    x1, w1, x2, w2, phase = 0.015, 2 * math.pi * 1.5, 0.006, 2 * math.pi * 4.1, 0.3
    two_sine = path + '.two_sine.csv'
    with open(two_sine, 'w') as f:
        f.write('t,x,v,a\n')
        for k in range(300):
            t = k / 250
            f.write(f'{t!r},{x1 * math.sin(w1 * t) + x2 * math.sin(w2 * t + phase)!r},'
                    f'{x1 * w1 * math.cos(w1 * t) + x2 * w2 * math.cos(w2 * t + phase)!r},'
                    f'{-x1 * w1 * w1 * math.sin(w1 * t) - x2 * w2 * w2 * math.sin(w2 * t + phase)!r}\n')
    subprocess.run([D, 'simulate', '--model', 'crfd.kwok', '--params', 'c_r=3,k_r=25,eta=0.5,mu=6,xi=0.8,T_r=0.011',
                    '--input', two_sine, '--noise-rel', '0.005', '--seed', '11', '-o', path], check=True)


def fit(args):
    start = time.time()
    r = subprocess.run([D, 'fit'] + args + ['--seed', '1', '--format', 'json', '--threads', '2'],
                       capture_output=True, text=True)
    if r.returncode != 0:
        return {'error': r.stderr.strip()[-400:]}
    j = json.loads(r.stdout)
    return {'best': j['runs']['best'], 'verdict': j['convergence']['verdict'], 'budget': j['budget'],
            'wall': time.time() - start}


def optimizer_args(name):
    o = OPTIMIZERS[name]
    return ['--optimizer', o[0]] + (['--optimizer-settings', o[1]] if len(o) > 1 else [])


# The sweep files' labels of fit_table's optimizers (bench/optimizers/algebraic.toml, ode.toml).
STORE_LABELS = {'cmaes-ipop': 'cmaes', 'cmaes-lm': 'ga-lm+cmaes', 'cmaes-sqp': 'ga-sqp+cmaes'}


def store_problem(model, fitset):
    """fit_table's name of a (model, fitset) group of run.sh's store, or None for a problem the table leaves out."""
    if model == 'crfd.kwok':
        return 'kwok'
    if model == 'fvd.gv_linear_elastic':
        return next((f'fvd{i}' for i, f in enumerate(FVD, 1) if f == fitset), None)
    if model in ('mrd.spencer', 'mrd.bouc_wen') and fitset in UTFSM_FILES:
        return f'{model.split(".")[1]}_{fitset}'
    return None


def cells_from_store(path):
    """(cells, best) as main() collects them, from the groups of run.sh's store: a group with the automatic budget
    is a cell (its stored message is the budget's summary), and every group, references included, sets the best
    known."""
    db = sqlite3.connect(f'file:{path}?mode=ro', uri=True)
    rows = db.execute("""
        SELECT m.name, f.label, o.label, g.status, g.message, g.wall_time_s, MIN(r.best_value)
        FROM groups g
        JOIN models m ON m.part = g.part AND m.model = g.model
        JOIN optimizers o ON o.part = g.part AND o.optimizer = g.optimizer
        JOIN fitsets f ON f.part = g.part AND f.split = g.split AND f.fitset = g.fitset
        LEFT JOIN runs r ON r.grp = g.grp
        GROUP BY g.grp""").fetchall()
    cells, best = {}, {}
    for model, fitset, label, status, message, wall, value in rows:
        p = store_problem(model, fitset)
        if p is None:
            continue
        value = math.inf if value is None else value
        best[p] = min(best.get(p, math.inf), value)
        if not message or status != 'done':
            continue  # a fixed budget (the references) or a failed group
        rounds = re.match(r'(\d+) rounds?', message)
        stop = 'converged' if ': converged' in message else ('cap' if 'stopped at the cap' in message else 'time cap')
        cells[(p, STORE_LABELS.get(label, label))] = {
            'best': value, 'verdict': 'converged' if stop == 'converged' else 'not converged', 'wall': wall,
            'budget': {'stop': stop, 'rounds': int(rounds.group(1)) if rounds else 1}, 'message': message}
    return cells, best


def print_table(names, opts, cells, best):
    print('| problem | best known | ' + ' | '.join(opts) + ' |')
    print('|---|---:|' + '---|' * len(opts))
    for p in names:
        row = []
        for o in opts:
            r = cells.get((p, o), {'error': 'not measured'})
            if 'error' in r:
                row.append('—' if r['error'] == 'not measured' else 'error')
                continue
            ratio = r['best'] / best[p]
            state = 'C' if r['verdict'] == 'converged' else ('cap' if r['budget'].get('stop') == 'cap' else r['verdict'])
            row.append(f"{state} {ratio:.4f}{'' if ratio <= 1.001 else ' ✗'} "
                       f"({r['budget'].get('rounds', 1)}r, {r['wall']:.0f}s)")
        print(f'| {p} | {best[p]:.6g} | ' + ' | '.join(row) + ' |')
    measured = [(p, o) for p in names for o in opts if 'error' not in cells.get((p, o), {'error': 1})]
    good = sum(cells[c]['verdict'] == 'converged' and cells[c]['best'] <= 1.001 * best[c[0]] for c in measured)
    capped = sum(cells[c]['budget'].get('stop') == 'cap' for c in measured)
    print(f'\n{good} of {len(measured)} measured pairs converged within 1.001x; {capped} stopped at the cap')


def main():
    args = sys.argv[1:]
    store = None
    if args[:1] == ['--store']:
        if len(args) < 2:
            sys.exit('fit_table.py: --store needs the path of run.sh\'s store.sqlite')
        store, args = args[1], args[2:]
    if store:
        cells, best = cells_from_store(store)
        known = list(problems('kwok_noisy.csv'))
        names = args[0].split(',') if args else [p for p in known if p in best]
        opts = args[1].split(',') if len(args) > 1 else list(OPTIMIZERS)
        print_table(names, opts, cells, best)
        return
    os.makedirs(OUT, exist_ok=True)
    kwok = os.path.join(OUT, 'kwok_noisy.csv')
    write_kwok(kwok)
    all_problems = problems(kwok)
    names = args[0].split(',') if args else list(all_problems)
    opts = args[1].split(',') if len(args) > 1 else list(OPTIMIZERS)
    cells, best = {}, {}
    log = open(os.path.join(OUT, 'cells_progress.jsonl'), 'w')  # each cell as it ends, for a run cut short
    for p in names:
        refs = ([('de', '50', '1000', '10'), ('cmaes', '50', '1000', '10')] if not p.startswith(('spencer', 'bouc'))
                else [('ga-lm', '24', '300', '4')])
        for name, pop, iters, runs in refs:
            r = fit(all_problems[p] + ['--optimizer', name, '--budget', 'fixed', '--pop', pop, '--iters', iters,
                                       '--runs', runs])
            best[p] = min(best.get(p, math.inf), r.get('best', math.inf))
        for o in opts:
            r = cells[(p, o)] = fit(all_problems[p] + optimizer_args(o))
            best[p] = min(best[p], r.get('best', math.inf))
            print(p, o, r.get('verdict', r.get('error')), f"{r.get('wall', 0):.1f}s", file=sys.stderr, flush=True)
            log.write(json.dumps({'problem': p, 'optimizer': o, **r}) + '\n')
            log.flush()
    with open(os.path.join(OUT, 'cells.jsonl'), 'w') as f:
        for (p, o), r in cells.items():
            f.write(json.dumps({'problem': p, 'optimizer': o, 'best_known': best[p], **r}) + '\n')
    print_table(names, opts, cells, best)


if __name__ == '__main__':
    main()

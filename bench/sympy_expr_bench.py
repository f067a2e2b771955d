#!/usr/bin/python3
"""SymPy half of the expression-engine comparison (see bench/expr_bench.cpp, docs/performance.md).

Run it with Debian's interpreter and python3-sympy, not a pyenv/venv python:
    /usr/bin/python3 bench/sympy_expr_bench.py [--sizes 3 6] [--timeout 120] [--json out.json]

The chain and the formulas are the ones of bench/chain_energy.hpp (change both together):
modified D-H, alpha_k = 0 (k even), +pi/2 (k = 1 mod 4), -pi/2 (k = 3 mod 4); a_k symbolic when
alpha_k = 0 and k > 0, d_i symbolic when alpha_k != 0; barycentric inertial parameters
(m, first moments mx my mz, inertia about the link origin xx xy xz yy yz zz), all symbols.
Vectors and matrices are plain lists of SymPy expressions, combined with the same formulas in the
same order as the C++ code, so both engines multiply out the same products.

Tasks, per chain size N (each run uses symbols with a new name suffix and starts from a cleared
SymPy cache, so no run profits from an earlier one, like the fresh dyncc benchmarks):
  build         T by link-to-link propagation (unexpanded)
  build_expand  build T, then sympy.expand(T)
  diff          sympy.diff: dT/dqd_i for all i, then d/dq_j of those, on the expanded T (input built
                and expanded outside the timer)
  zero_*        prove T_body - T_world == 0 (T from link-frame propagation minus T from base-frame
                forward kinematics; true only through sin^2 + cos^2 = 1). Input built outside the
                timer. Four methods, all reported; the comparison uses the fastest:
    zero_ring        convert the unexpanded difference into the sparse polynomial ring
                     QQ[sin q_i, cos q_i, other symbols] (sympy.polys.rings), memoised over shared
                     subexpressions, reducing every product modulo {sin^2 q_i + cos^2 q_i - 1}
                     (PolyElement.rem). Those relations are a Groebner basis, so the result is 0
                     exactly for an identity: the decision procedure dyncc's test_zero uses.
    zero_ring_final  the same, but one reduction at the end (faster for N = 3, far slower for N = 6)
    zero_reduced     expression level: sympy.expand(difference), then
                     sympy.reduced(expanded, [sin(q_i)**2 + cos(q_i)**2 - 1]), remainder == 0
    zero_trigsimp    sympy.trigsimp(sympy.expand(difference)) == 0, what a user would try first
Times are CPU seconds of this process (the benchmark machine is shared). Every run has a CPU-time
limit (--timeout, --side-timeout for the context-only zero methods); a run over it is reported as
"> X s", and the same task is not tried on a larger chain. Short tasks are repeated (up to
--repeat runs or --budget CPU seconds) and the median is reported.
"""

import argparse
import json
import platform
import signal
import statistics
import sys
import time

import sympy
from sympy import Add, Integer, Rational, Symbol, cos, sin
from sympy.core.cache import clear_cache


# ---- the chain (mirrors bench/chain_energy.hpp) ----

class Link:
    pass


def make_chain(n, suffix):
    def s(base, i):
        return Symbol(f"{base}{i}{suffix}")

    chain = []
    for i in range(1, n + 1):
        k = i - 1
        l = Link()
        l.alpha_quarter_turns = 0 if k % 2 == 0 else (1 if k % 4 == 1 else -1)
        l.a = s("a", k) if (l.alpha_quarter_turns == 0 and k > 0) else Integer(0)
        l.d = s("d", i) if l.alpha_quarter_turns != 0 else Integer(0)
        l.q = s("q", i)
        l.qd = s("qd", i)
        l.m = s("m", i)
        l.h = [s("mx", i), s("my", i), s("mz", i)]
        xx, xy, xz, yy, yz, zz = (s(b, i) for b in ("xx", "xy", "xz", "yy", "yz", "zz"))
        l.I = [[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]]
        chain.append(l)
    return chain


def vadd(a, b):
    return [a[0] + b[0], a[1] + b[1], a[2] + b[2]]


def vsub(a, b):
    return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]


def vscale(s, a):
    return [s * a[0], s * a[1], s * a[2]]


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def mat_vec(m, v):
    return [dot(m[0], v), dot(m[1], v), dot(m[2], v)]


def mat_t_vec(m, v):
    return [m[0][0] * v[0] + m[1][0] * v[1] + m[2][0] * v[2],
            m[0][1] * v[0] + m[1][1] * v[1] + m[2][1] * v[2],
            m[0][2] * v[0] + m[1][2] * v[1] + m[2][2] * v[2]]


def mat_mul(a, b):
    return [[a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j] for j in range(3)] for i in range(3)]


def transposed(m):
    return [[m[0][0], m[1][0], m[2][0]], [m[0][1], m[1][1], m[2][1]], [m[0][2], m[1][2], m[2][2]]]


def joint_rotation(l):
    ca = Integer(1 if l.alpha_quarter_turns == 0 else 0)
    sa = Integer(l.alpha_quarter_turns)
    c, s = cos(l.q), sin(l.q)
    return [[c, -s, Integer(0)], [ca * s, ca * c, -sa], [sa * s, sa * c, ca]]


def joint_offset(l):
    ca = Integer(1 if l.alpha_quarter_turns == 0 else 0)
    sa = Integer(l.alpha_quarter_turns)
    return [l.a, -sa * l.d, ca * l.d]


def link_energy(l, v, w, h, I):
    half = Rational(1, 2)
    return half * l.m * dot(v, v) + dot(v, cross(w, h)) + half * dot(w, mat_vec(I, w))


def kinetic_energy_body(chain):
    zero = Integer(0)
    w = [zero, zero, zero]
    v = [zero, zero, zero]
    T = zero
    for l in chain:
        R = joint_rotation(l)
        p = joint_offset(l)
        v_new = mat_t_vec(R, vadd(v, cross(w, p)))
        w_new = mat_t_vec(R, w)
        w_new[2] = w_new[2] + l.qd
        v, w = v_new, w_new
        T = T + link_energy(l, v, w, l.h, l.I)
    return T


def kinetic_energy_world(chain):
    zero, one = Integer(0), Integer(1)
    R0 = [[one, zero, zero], [zero, one, zero], [zero, zero, one]]
    p0 = [zero, zero, zero]
    axes, origins = [], []
    T = zero
    for l in chain:
        p0 = vadd(p0, mat_vec(R0, joint_offset(l)))
        R0 = mat_mul(R0, joint_rotation(l))
        axes.append([R0[0][2], R0[1][2], R0[2][2]])
        origins.append(p0)
        w = [zero, zero, zero]
        v = [zero, zero, zero]
        for k in range(len(axes)):
            qd = chain[k].qd
            w = vadd(w, vscale(qd, axes[k]))
            v = vadd(v, vscale(qd, cross(axes[k], vsub(p0, origins[k]))))
        h0 = mat_vec(R0, l.h)
        I0 = mat_mul(mat_mul(R0, l.I), transposed(R0))
        T = T + link_energy(l, v, w, h0, I0)
    return T


def cpu_clock():
    return time.process_time()


class Stopwatch:
    """CPU and wall-clock seconds over the same interval."""

    def __init__(self):
        self.cpu, self.wall = cpu_clock(), time.perf_counter()

    def stop(self):
        return (cpu_clock() - self.cpu, time.perf_counter() - self.wall)


def term_count(e):
    return 0 if e == 0 else len(Add.make_args(e))


# ---- the tasks; each takes a fresh chain and returns (timed seconds, info dict) ----

def task_build(chain):
    watch = Stopwatch()
    kinetic_energy_body(chain)
    return watch.stop(), {}


def task_build_expand(chain):
    watch = Stopwatch()
    T = sympy.expand(kinetic_energy_body(chain))
    dt = watch.stop()
    return dt, {"terms": term_count(T)}


def task_diff(chain):
    T = sympy.expand(kinetic_energy_body(chain))
    watch = Stopwatch()
    terms = 0
    for li in chain:
        dT = sympy.diff(T, li.qd)
        terms += term_count(dT)
        for lj in chain:
            terms += term_count(sympy.diff(dT, lj.q))
    return watch.stop(), {"terms": terms}


def pythagorean_relations(chain):
    return [sin(l.q) ** 2 + cos(l.q) ** 2 - 1 for l in chain]


def to_ring(expr, R, relations=None):
    """Unexpanded expression -> ring element, memoised over shared subexpressions.

    sympy's own R(expr) does the same walk without a memo, which re-multiplies every shared
    subtree (the world-frame T shares rotation products heavily). With `relations`, every
    product is reduced modulo them at once (PolyElement.rem), which keeps the polynomials small.
    """
    mapping = dict(zip(R.symbols, R.gens))
    memo = {}

    def reduce(p):
        return p if relations is None else p.rem(relations)

    def rebuild(e):
        g = mapping.get(e)
        if g is not None:
            return g
        r = memo.get(e)
        if r is not None:
            return r
        if e.is_Add:
            args = [rebuild(a) for a in e.args]
            r = args[0]
            for a in args[1:]:
                r = r + a
        elif e.is_Mul:
            args = [rebuild(a) for a in e.args]
            r = args[0]
            for a in args[1:]:
                r = reduce(r * a)
        elif e.is_Pow and e.exp.is_Integer and e.exp > 1:
            r = reduce(rebuild(e.base) ** int(e.exp))
        else:
            r = R.ground_new(R.domain.convert(e))
        memo[e] = r
        return r

    return rebuild(expr)


def zero_difference(chain):
    return kinetic_energy_body(chain) - kinetic_energy_world(chain)


def ring_and_relations(chain, difference):
    trig = []
    for l in chain:
        trig += [sin(l.q), cos(l.q)]
    others = sorted(difference.free_symbols - {l.q for l in chain}, key=lambda s: s.name)
    R, *gens = sympy.polys.rings.ring(trig + others, sympy.QQ)
    return R, [gens[2 * i] ** 2 + gens[2 * i + 1] ** 2 - 1 for i in range(len(chain))]


def task_zero_ring(chain):
    difference = zero_difference(chain)
    watch = Stopwatch()
    R, relations = ring_and_relations(chain, difference)
    p = to_ring(difference, R, relations)
    dt = watch.stop()
    if p != 0:
        raise RuntimeError("zero_ring: T_body - T_world did not reduce to 0")
    return dt, {}


def task_zero_ring_final(chain):
    difference = zero_difference(chain)
    watch = Stopwatch()
    R, relations = ring_and_relations(chain, difference)
    p = to_ring(difference, R)
    remainder = p.rem(relations)
    dt = watch.stop()
    if remainder != 0:
        raise RuntimeError("zero_ring_final: T_body - T_world did not reduce to 0")
    return dt, {"terms_before_reduction": len(p)}


def task_zero_reduced(chain):
    difference = zero_difference(chain)
    watch = Stopwatch()
    expanded = sympy.expand(difference)
    _, remainder = sympy.reduced(expanded, pythagorean_relations(chain))
    dt = watch.stop()
    if remainder != 0:
        raise RuntimeError("zero_reduced: T_body - T_world did not reduce to 0")
    return dt, {"expanded_terms": term_count(expanded)}


def task_zero_trigsimp(chain):
    difference = zero_difference(chain)
    watch = Stopwatch()
    result = sympy.trigsimp(sympy.expand(difference))
    dt = watch.stop()
    if result != 0:
        raise RuntimeError("zero_trigsimp: trigsimp did not reduce T_body - T_world to 0")
    return dt, {}


TASKS = {
    "build": task_build,
    "build_expand": task_build_expand,
    "diff": task_diff,
    "zero_ring": task_zero_ring,
    "zero_ring_final": task_zero_ring_final,
    "zero_reduced": task_zero_reduced,
    "zero_trigsimp": task_zero_trigsimp,
}
# The zero-test methods other than the fastest are context only: they get --side-timeout.
SIDE_TASKS = {"zero_ring_final", "zero_reduced", "zero_trigsimp"}


class Timeout(Exception):
    pass


def _on_timer(signum, frame):
    raise Timeout()


_run_counter = 0


def measure(task, n, timeout, repeat, budget):
    """Median CPU seconds of up to `repeat` runs (fewer once `budget` CPU seconds are spent).

    Each run gets a fresh chain (new symbol names) and a cleared SymPy cache. The timeout is on
    the CPU time of the run (ITIMER_PROF), like the measurement, so a loaded machine does not turn
    a slow run into a timeout; the wall-clock time of each run is recorded too.
    """
    global _run_counter
    times, walls, info = [], [], {}
    started = cpu_clock()
    for _ in range(repeat):
        _run_counter += 1
        clear_cache()
        chain = make_chain(n, f"_r{_run_counter}")
        signal.signal(signal.SIGPROF, _on_timer)
        signal.setitimer(signal.ITIMER_PROF, timeout)
        try:
            (dt, dt_wall), info = task(chain)
        except Timeout:
            return {"timeout": timeout}
        finally:
            signal.setitimer(signal.ITIMER_PROF, 0)
        walls.append(dt_wall)
        times.append(dt)
        if cpu_clock() - started > budget:
            break
    return {"seconds": statistics.median(times), "runs": len(times), "wall_seconds": statistics.median(walls), **info}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--sizes", type=int, nargs="+", default=[3, 6])
    parser.add_argument("--tasks", nargs="+", default=list(TASKS), choices=list(TASKS))
    parser.add_argument("--timeout", type=float, default=120.0, help="CPU seconds per run of a main task")
    parser.add_argument("--side-timeout", type=float, default=30.0,
                        help="CPU seconds per run of the slower zero-test methods (context only)")
    parser.add_argument("--repeat", type=int, default=5, help="runs per measurement at most")
    parser.add_argument("--budget", type=float, default=10.0, help="stop repeating after this many CPU seconds")
    parser.add_argument("--json", help="write the results here (default: stdout)")
    args = parser.parse_args()

    results = {
        "python": platform.python_version(),
        "python_executable": sys.executable,
        "sympy": sympy.__version__,
        "ground_types": sympy.external.gmpy.GROUND_TYPES,
        "clock": "CPU time of the process (time.process_time)",
        "timeout": args.timeout,
        "side_timeout": args.side_timeout,
        "results": {},
    }
    timed_out = set()
    for n in sorted(args.sizes):
        for name in args.tasks:
            timeout = args.side_timeout if name in SIDE_TASKS else args.timeout
            if name in timed_out:
                # A larger chain only takes longer: do not spend another timeout on it.
                r = {"timeout": timeout, "skipped": "timed out on a smaller chain"}
            else:
                r = measure(TASKS[name], n, timeout, args.repeat, args.budget)
            if "timeout" in r:
                timed_out.add(name)
            results["results"][f"{name}/{n}"] = r
            shown = f"> {timeout:g} s (timeout)" if "timeout" in r else f"{r['seconds']:.4g} s"
            extra = " ".join(f"{k}={v}" for k, v in r.items() if k not in ("seconds", "timeout"))
            print(f"sympy {name}/{n}: {shown} {extra}", file=sys.stderr, flush=True)
    text = json.dumps(results, indent=2)
    if args.json:
        with open(args.json, "w", encoding="utf-8") as f:
            f.write(text + "\n")
    else:
        print(text)


if __name__ == "__main__":
    main()

"""The explore server (``acausal2d explore``) under load.  Prints a table.

    python benchmarks/bench_explore.py [--small]

The server is started as a user starts it (``acausal2d explore
models/piston_engine.py --port 0``, its own process) and asked over HTTP:

round trip    = a parameter change (bodyPiston.m) with 2 s simulated, 500
                intervals, the model's figures' signals: request to answer,
                median and 90th percentile over the changes (target: median
                <= 0.15 s), and the median of the run alone (the answer's
                elapsed_s: what the server's simulate took); also with the animation page in the answer
                ("scene": true), as the page asks
concurrent    = eight clients (threads), each with its own session, making
                their runs at the same time; every answer is compared with
                the same run made alone afterwards: the largest difference
                in units of rtol times the signal's magnitude (0 = equal)
memory        = the server's resident memory (VmRSS) after the first tenth
                of 1000 runs with changing parameters and after all of them;
                bounded when the last half of the runs adds less than 20 MB
--small runs fewer changes and 100 instead of 1000 runs (for the suite).
"""
import json
import os
import signal
import statistics
import subprocess
import sys
import threading
import time
import urllib.request

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
RTOL = 1e-8               # the piston engine's experiment rtol
BOUND_MB = 20.0


def start_server():
    """(process, url) of a fresh explore server on a free port."""
    proc = subprocess.Popen([sys.executable, "-m", "acausal2d", "explore",
                             "models/piston_engine.py", "--port", "0"], cwd=ROOT,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    url = proc.stdout.readline().strip()
    if not url.startswith("http://127.0.0.1:"):
        proc.kill()
        raise SystemExit("the server did not start: %s" % proc.stderr.read()[-2000:])
    return proc, url


def run(url, body):
    """(seconds, answer) of one POST /api/run."""
    data = json.dumps(body).encode()
    t0 = time.perf_counter()
    base, _, token = url.partition("?token=")           # the page's URL carries the API token
    req = urllib.request.Request(base + "api/run", data=data, headers={
        "Content-Type": "application/json", "X-Acausal2d-Token": token})
    with urllib.request.urlopen(req, timeout=300) as r:
        answer = json.loads(r.read())
    return time.perf_counter() - t0, answer


def change(k):
    return {"set": {"bodyPiston.m": 2.0 + 0.01 * (k % 200)}, "stop_time": 2.0}


def round_trips(url, n, scene):
    """(median, 90th percentile, median of the runs' own elapsed_s) in s."""
    answers = [run(url, dict(change(k), scene=scene)) for k in range(1, n + 1)]
    times = sorted(t for t, _ in answers)
    return (statistics.median(times), times[int(0.9 * (len(times) - 1))],
            statistics.median(a["elapsed_s"] for _, a in answers))


def worst_difference(a, b):
    """Largest |a - b| over the signals, in units of RTOL * (|b| + 1)."""
    worst = 0.0
    for name, values in b["signals"].items():
        for x, y in zip(a["signals"][name], values):
            worst = max(worst, abs(x - y) / (RTOL * (abs(y) + 1.0)))
    return worst


def concurrent(url, clients=8, each=3):
    """(largest difference, answers compared): eight clients at once."""
    bodies = [[{"set": {"bodyPiston.m": 1.0 + 0.3 * c, "crank.r": [0.25 + 0.02 * k, 0]},
                "stop_time": 2.0, "session": "client-%d" % c} for k in range(each)]
              for c in range(clients)]
    answers = [[None] * each for _ in range(clients)]

    def client(c):
        for k, body in enumerate(bodies[c]):
            answers[c][k] = run(url, body)[1]
    threads = [threading.Thread(target=client, args=(c,)) for c in range(clients)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    worst = 0.0
    for c in range(clients):
        for k in range(each):
            worst = max(worst, worst_difference(answers[c][k], run(url, bodies[c][k])[1]))
    return worst, clients * each


def rss_mb(pid):
    with open("/proc/%d/status" % pid) as fh:
        for line in fh:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024.0
    return float("nan")


def memory(url, pid, runs):
    """RSS (MB) after a tenth, half and all of ``runs`` runs."""
    marks = {}
    for k in range(1, runs + 1):
        run(url, change(k))
        if k in (runs // 10, runs // 2, runs):
            marks[k] = rss_mb(pid)
    return marks[runs // 10], marks[runs // 2], marks[runs]


def main(small=False):
    proc, url = start_server()
    try:
        median, p90, alone = round_trips(url, 8 if small else 60, False)
        s_median, s_p90, _ = round_trips(url, 4 if small else 20, True)
        worst, compared = concurrent(url, 8, 1 if small else 3)
        runs = 100 if small else 1000
        tenth, half, last = memory(url, proc.pid, runs)
    finally:
        proc.send_signal(signal.SIGINT)
        proc.wait(timeout=60)
    bounded = last - half < BOUND_MB
    print("explore server, piston engine, 2 s simulated per run (%s mode)"
          % ("small" if small else "full"))
    print("%-44s %10s %10s" % ("", "median", "p90"))
    print("%-44s %10.4f %10.4f" % ("round trip of a change [s] (target 0.15)", median, p90))
    print("%-44s %10.4f" % ("  of which the run itself (elapsed_s) [s]", alone))
    print("%-44s %10.4f %10.4f" % ("round trip with the animation page [s]", s_median, s_p90))
    print("%-44s %10.4f" % ("8 concurrent clients: worst diff [rtol units]", worst))
    print("%-44s %10d" % ("8 concurrent clients: answers compared", compared))
    print("%-44s %10.1f %10.1f" % ("server memory [MB] after %d / %d runs" % (runs // 10, runs),
                                   tenth, last))
    print("%-44s %10.1f" % ("memory growth over the last %d runs [MB]" % (runs - runs // 2),
                            last - half))
    print("memory bounded (last half adds < %g MB): %s" % (BOUND_MB, "yes" if bounded else "NO"))
    print("concurrent answers equal to the runs made alone: %s"
          % ("yes" if worst <= 1.0 else "NO"))
    return 0 if bounded and worst <= 1.0 else 1


if __name__ == "__main__":
    sys.exit(main("--small" in sys.argv[1:]))

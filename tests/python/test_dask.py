"""Dask as the evaluator: a scheduler and two workers on loopback, a small GA through them.

The logbook must be byte-identical to the local run's, and a worker killed while it holds tasks
must lose nothing: Dask gives its tasks to the other worker, and the run ends as if nothing happened.
"""
import os
import signal
import subprocess
import sys
import threading
import time

import pytest

import actuator

distributed = pytest.importorskip("distributed")  # python3-distributed, in scripts/install-deps.sh

GA = {"id": "dask", "seed": 11, "model": {"name": "thesis"}, "sim": {"iterations": 10000},
      "evolve": {"runs": 1, "population": 16, "generations": 6, "genome": {"kind": "bspline", "length": [5, 8]}},
      "render": {"figures": False, "thumbnails": False}}
COMPARED = ("run_1/logbook.csv", "run_1/halloffame.csv", "run_1/checkpoint.json")


def start(args, log):
    return subprocess.Popen([sys.executable, "-m", *args], stdout=log, stderr=subprocess.STDOUT, env=os.environ.copy())


@pytest.fixture
def cluster(tmp_path):
    """(client, {name: worker process}): a scheduler and workers w1, w2 on 127.0.0.1, no nanny
    (a killed worker stays dead), one thread each."""
    log = open(tmp_path / "dask.log", "w")
    scheduler_file = str(tmp_path / "scheduler.json")
    processes = [start(["distributed.cli.dask_scheduler", "--host", "127.0.0.1", "--port", "0", "--no-dashboard",
                        "--scheduler-file", scheduler_file], log)]
    workers = {}
    try:
        deadline = time.time() + 60
        while not os.path.exists(scheduler_file) and time.time() < deadline:
            time.sleep(0.05)
        for name in ("w1", "w2"):
            workers[name] = start(["distributed.cli.dask_worker", "--scheduler-file", scheduler_file, "--name", name, "--nthreads", "1",
                                   "--no-nanny", "--no-dashboard", "--local-directory", str(tmp_path / name)], log)
            processes.append(workers[name])
        client = distributed.Client(scheduler_file=scheduler_file, timeout=60)
        client.wait_for_workers(2, timeout=60)
        yield client, workers
        client.close()
    finally:
        for p in processes:
            p.kill()
            p.wait()
        log.close()


def test_a_ga_through_dask_equals_the_local_run_even_when_a_worker_dies(cluster, tmp_path):
    client, workers = cluster
    actuator.evolve(GA, str(tmp_path / "local"), threads=2)

    # Kill w1 once the first generation is logged and w1 is busy with the next one's tasks.
    out = tmp_path / "dask"
    killed = threading.Event()

    def kill_w1_mid_run():
        w1 = next(address for address, info in client.scheduler_info()["workers"].items() if info["name"] == "w1")
        deadline = time.time() + 120
        while time.time() < deadline and not killed.is_set():
            if (out / "run_1" / "checkpoint.json").exists() and client.processing().get(w1):
                workers["w1"].send_signal(signal.SIGKILL)
                killed.set()
                return
            time.sleep(0.002)

    killer = threading.Thread(target=kill_w1_mid_run)
    killer.start()
    result = actuator.evolve(GA, str(out), map=client)
    killer.join()
    assert killed.is_set(), "the GA ended before a worker could be killed in the middle of it"
    assert workers["w1"].wait(timeout=10) == -signal.SIGKILL
    assert len(client.scheduler_info()["workers"]) == 1
    for name in COMPARED:
        assert (out / name).read_bytes() == (tmp_path / "local" / name).read_bytes(), name
    assert result["summary"]["simulations"] > 0


def test_evaluate_many_through_a_dask_client_is_bit_for_bit(cluster):
    client, _ = cluster
    import math
    shapes = [actuator.sine(a, (0.5, math.pi - 0.5)) for a in (1.0, 2.0, 3.0, 4.1)]
    params = actuator.ThesisParams(iterations=3000)
    local = [(r.fitness.hex(), r.final.tobytes()) for r in actuator.evaluate_many(shapes, threads=1, params=params, model="thesis")]
    remote = [(r.fitness.hex(), r.final.tobytes()) for r in actuator.evaluate_many(shapes, map=client, params=params, model="thesis")]
    assert remote == local

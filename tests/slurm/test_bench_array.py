#!/usr/bin/env python3
"""scripts/slurm/bench_array.sh on a single-node Slurm cluster started here, against one plain bench.

Writes a minimal slurm.conf for this machine in a temporary folder (no munge: auth/none, the node is
127.0.0.1, ports picked free), starts slurmctld and slurmd in the foreground as children, submits a
tiny suite as a job array of 3 shards with the merge job, waits for the merge, and checks that

  * every shard and the merge ran as Slurm jobs (their logs, bench-shard-<i>.json),
  * the merged report holds every run of the suite, and
  * each room's run.json (metrics, objects, steps; not the timings) and the report's tables equal
    those of one un-sharded `objscan bench` of the same suite.

Needs root (slurmd runs jobs as their user) and Debian's slurm-wlm; without them it prints SKIP and
exits 77, which ctest reports as skipped (SKIP_RETURN_CODE), never as passed.

Environment (set by ctest): OBJSCAN_BINARY, OBJSCAN_TEST_DB (a small database), OBJSCAN_SOURCE_DIR.
"""
import json
import os
import shutil
import socket
import subprocess
import sys
import tempfile
import time

SKIP = 77
SUITE_ARGS = ["--suite", "procedural", "--seeds", "1", "--methods", "ours", "--set", "scanner.max_steps=2"]
SHARDS = 3
# Fields of run.json and results.json that depend on the machine's speed and load, or on the folder.
VOLATILE = {"timing_s", "timing_ms", "peak_rss_mb", "cpu_s", "compute_s", "table3", "wall_s", "seconds", "resources"}


def skip(why):
    print(f"SKIP: {why}", file=sys.stderr)
    print(f"SKIP: {why}")
    return SKIP


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def strip(value, out_dir):
    if isinstance(value, dict):
        return {k: strip(v, out_dir) for k, v in value.items() if k not in VOLATILE}
    if isinstance(value, list):
        return [strip(v, out_dir) for v in value]
    if isinstance(value, str):
        return value.replace(out_dir, "OUT")
    return value


def write_slurm_conf(root):
    host = socket.gethostname().split(".")[0]
    conf = os.path.join(root, "slurm.conf")
    for d in ("state", "spool"):
        os.makedirs(os.path.join(root, d), exist_ok=True)
    with open(conf, "w") as f:
        f.write(f"""# A one-node cluster for tests/slurm/test_bench_array.py
ClusterName=objscantest
SlurmctldHost={host}(127.0.0.1)
SlurmUser=root
SlurmdUser=root
SlurmctldPort={free_port()}
SlurmdPort={free_port()}
AuthType=auth/none
CredType=cred/none
StateSaveLocation={root}/state
SlurmdSpoolDir={root}/spool
SlurmctldPidFile={root}/slurmctld.pid
SlurmdPidFile={root}/slurmd.pid
SlurmctldLogFile={root}/slurmctld.log
SlurmdLogFile={root}/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
MpiDefault=none
ReturnToService=2
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
NodeName={host} NodeAddr=127.0.0.1 CPUs={os.cpu_count() or 1} State=UNKNOWN
PartitionName=objscan Nodes={host} Default=YES MaxTime=INFINITE State=UP
""")
    return conf, host


def wait_for_node(env, host, daemons, seconds=60):
    deadline = time.time() + seconds
    while time.time() < deadline:
        for name, p in daemons:
            if p.poll() is not None:
                raise RuntimeError(f"{name} exited with status {p.returncode}")
        r = subprocess.run(["sinfo", "-h", "-n", host, "-o", "%T"], capture_output=True, text=True, env=env)
        if r.returncode == 0 and r.stdout.strip().startswith("idle"):
            return
        time.sleep(0.5)
    raise RuntimeError(f"the node {host} did not come up idle in {seconds} s")


def cgroup_failure(root):
    """The line of the daemons' logs saying the cgroup file system is missing, or None."""
    for name in ("slurmd.log", "slurmd.stderr", "slurmctld.log", "slurmctld.stderr"):
        path = os.path.join(root, name)
        if not os.path.exists(path):
            continue
        with open(path, errors="replace") as f:
            for line in f:
                if "cgroup" in line and ("not mounted" in line or "cannot" in line.lower() or "error" in line.lower()):
                    return line.strip()
    return None


def load(path):
    with open(path) as f:
        return json.load(f)


def runs_of(out):
    """{scene/method: run.json} of a bench folder."""
    runs = {}
    root = os.path.join(out, "runs")
    for scene in sorted(os.listdir(root)):
        for method in sorted(os.listdir(os.path.join(root, scene))):
            path = os.path.join(root, scene, method, "run.json")
            if os.path.exists(path):
                runs[f"{scene}/{method}"] = load(path)
    return runs


def main():
    if os.geteuid() != 0:
        return skip("the Slurm test needs root (slurmd starts jobs as their user); run ctest as root")
    missing = [t for t in ("slurmctld", "slurmd", "sbatch", "sinfo", "squeue") if shutil.which(t) is None]
    if missing:
        return skip(f"Slurm is not installed ({', '.join(missing)} missing): apt-get install slurm-wlm "
                    "(scripts/install_deps.sh)")
    objscan = os.environ["OBJSCAN_BINARY"]
    db = os.environ["OBJSCAN_TEST_DB"]
    script = os.path.join(os.environ["OBJSCAN_SOURCE_DIR"], "scripts", "slurm", "bench_array.sh")
    root = tempfile.mkdtemp(prefix="objscan_slurm_")
    conf, host = write_slurm_conf(root)
    env = dict(os.environ, SLURM_CONF=conf)
    # The jobs inherit this environment: the bench needs no database cache, but keep any away from $HOME.
    env["OBJSCAN_CACHE_DIR"] = os.path.join(root, "cache")
    daemons = []
    ok = False
    try:
        for name in ("slurmctld", "slurmd"):
            log = open(os.path.join(root, f"{name}.stderr"), "w")
            daemons.append((name, subprocess.Popen([name, "-D", "-f", conf], env=env, stdout=log, stderr=log)))
        try:
            wait_for_node(env, host, daemons)
        except RuntimeError:
            # slurmd needs the cgroup file system (a fresh root without /sys/fs/cgroup mounted, as some
            # containers are): what the machine lacks is a skip, said loudly, not a failure of the script.
            reason = cgroup_failure(root)
            if reason:
                ok = True
                return skip(f"slurmd cannot start on this machine: {reason} (mount the cgroup file system "
                            "to run this test)")
            raise
        print(f"slurm: one node '{host}' up ({root})")

        sharded = os.path.join(root, "sharded")
        start = time.time()
        r = subprocess.run([script, "--shards", str(SHARDS), "--out", sharded, "--objscan", objscan, "--wait", "--",
                            *SUITE_ARGS, "--db", db], capture_output=True, text=True, env=env, timeout=1800)
        print(r.stdout.strip())
        assert r.returncode == 0, f"bench_array.sh: status {r.returncode}\n{r.stderr}"
        submitted = json.loads(r.stdout.strip().splitlines()[-1])
        print(f"slurm: array {submitted['array_job']} + merge {submitted['merge_job']} in {time.time() - start:.1f} s")
        for i in range(1, SHARDS + 1):
            log = os.path.join(sharded, "slurm", f"shard-{i}.log")
            assert os.path.exists(log), log
            with open(log) as f:
                assert f"shard {i}/{SHARDS}" in f.read(), log
            shard = load(os.path.join(sharded, f"bench-shard-{i}.json"))
            assert shard["shard"] == f"{i}/{SHARDS}" and shard["runs_failed"] == 0, shard
        with open(os.path.join(sharded, "slurm", "merge.log")) as f:
            merge_log = f.read()
        merged = json.loads(merge_log[merge_log.index("{"):])
        assert merged["runs_failed"] == 0, merged

        single = os.path.join(root, "single")
        start = time.time()
        r = subprocess.run([objscan, "bench", *SUITE_ARGS, "--db", db, "--jobs", "2", "--out", single],
                           capture_output=True, text=True, env=env, timeout=1800)
        assert r.returncode == 0, f"objscan bench: status {r.returncode}\n{r.stderr}"
        print(f"single bench: {time.time() - start:.1f} s")

        a, b = runs_of(sharded), runs_of(single)
        assert len(b) == 5, sorted(b)
        assert sorted(a) == sorted(b), (sorted(a), sorted(b))
        assert merged["runs_complete"] == len(b), merged
        for name in b:
            ra, rb = strip(a[name], sharded), strip(b[name], single)
            assert ra["metrics"] == rb["metrics"], f"{name}: metrics differ"
            assert ra == rb, f"{name}: run.json differs"
            print(f"{name}: recall {rb['metrics']['recall']:.3f} precision {rb['metrics']['precision']:.3f} "
                  f"coverage {rb['metrics']['coverage_rate']:.3f} (same in both)")
        ja = strip(load(os.path.join(sharded, "report", "results.json")), sharded)
        jb = strip(load(os.path.join(single, "report", "results.json")), single)
        assert ja["runs"] == jb["runs"], (ja["runs"], jb["runs"])
        for key in jb:
            assert ja.get(key) == jb[key], f"results.json '{key}' differs"
        assert ja == jb
        print(f"merged report of {SHARDS} shards = single bench: {len(b)} runs, table1 {len(jb['table1'])} rows")
        ok = True
        return 0
    finally:
        # Jobs still running (a timeout) are cancelled before the daemons stop, so no job step outlives them.
        if daemons and daemons[0][1].poll() is None:
            subprocess.run(["scancel", "--partition", "objscan"], env=env, capture_output=True, timeout=60)
            time.sleep(2)
        for name, p in reversed(daemons):
            if p.poll() is None:
                p.terminate()
                try:
                    p.wait(timeout=20)
                except subprocess.TimeoutExpired:
                    p.kill()
                    p.wait()
        if not ok:
            for name in ("slurmctld.log", "slurmd.log", "slurmctld.stderr", "slurmd.stderr"):
                path = os.path.join(root, name)
                if os.path.exists(path):
                    with open(path) as f:
                        print(f"--- {name} (last lines)\n" + "".join(f.readlines()[-25:]), file=sys.stderr)
            for d in ("sharded/slurm",):
                folder = os.path.join(root, d)
                if os.path.isdir(folder):
                    for name in sorted(os.listdir(folder)):
                        with open(os.path.join(folder, name)) as f:
                            print(f"--- {d}/{name}\n" + f.read()[-3000:], file=sys.stderr)
            print(f"(kept {root})", file=sys.stderr)
        else:
            shutil.rmtree(root, ignore_errors=True)


if __name__ == "__main__":
    try:
        sys.exit(main())
    except AssertionError as e:
        print(f"FAILED: {e}", file=sys.stderr)
        sys.exit(1)

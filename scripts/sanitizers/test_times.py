#!/usr/bin/env python3
# Runs the ctest tests of a build in LANES parallel lanes and appends one JSON line per test to OUT:
# its wall, user and sys seconds (CPU time includes the programs it starts). CPU time, unlike
# ctest's wall time, does not grow when other work shares the machine. Usage:
#   scripts/sanitizers/test_times.py BUILD LANES OUT.jsonl [REGEX]
# Set the sanitizer environment of scripts/test.sh first when BUILD is build-sanitize. A test
# that fails has the last 20 kB of its output appended to OUT.fail.log.
import json, os, subprocess, sys, time, threading, resource, signal
build, lanes, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
regex = sys.argv[4] if len(sys.argv) > 4 else None
import re
info = json.loads(subprocess.check_output(['ctest', '--test-dir', build, '--show-only=json-v1']))
tests = []
for t in info['tests']:
    props = {p['name']: p['value'] for p in t.get('properties', [])}
    if props.get('DISABLED'): continue
    if regex and not re.search(regex, t['name']): continue
    tests.append((t['name'], t['command'], props.get('WORKING_DIRECTORY', build), props.get('ENVIRONMENT', [])))
lock = threading.Lock()
results = []
idx = [0]
def worker():
    while True:
        with lock:
            if idx[0] >= len(tests): return
            name, cmd, wd, envl = tests[idx[0]]; idx[0] += 1
        env = dict(os.environ)
        for e in envl:
            k, v = e.split('=', 1); env[k] = v
        start = time.time()
        p = subprocess.Popen(cmd, cwd=wd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, start_new_session=True)
        timer = threading.Timer(3600, lambda: os.killpg(p.pid, signal.SIGKILL))
        timer.start()
        output = p.stdout.read()
        _, status, ru = os.wait4(p.pid, 0)
        timer.cancel()
        wall = time.time() - start
        rc = os.waitstatus_to_exitcode(status)
        with lock:
            results.append((name, rc, wall, ru.ru_utime, ru.ru_stime))
            with open(out, 'a') as f:
                f.write(json.dumps({'name': name, 'rc': rc, 'wall': round(wall, 2), 'user': round(ru.ru_utime, 2), 'sys': round(ru.ru_stime, 2)}) + '\n')
            if rc != 0:
                with open(out + '.fail.log', 'ab') as f:
                    f.write(('==== ' + name + ' rc=%d\n' % rc).encode()); f.write(output[-20000:])
ths = [threading.Thread(target=worker) for _ in range(lanes)]
[t.start() for t in ths]; [t.join() for t in ths]

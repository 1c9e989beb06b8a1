"""Where the world server spends its time while a bench part runs: py-spy (tools/requirements.txt) on the running
process, summarized by function (self time) and by racebot's frames (inclusive)."""
import math
import os
import shutil
import subprocess

from . import common


def pyspy():
    here = os.path.join(os.path.dirname(common.python()), 'py-spy')
    return here if os.path.exists(here) else shutil.which('py-spy')


def profile_world_server(pid, seconds, out, name='world_server'):
    """Where the world server's update loop spends its time: py-spy (if installed) on the running
    process, its main thread, by function (self time) and by our functions (inclusive)."""
    exe = pyspy()
    if exe is None:
        return {'available': False, 'why': 'py-spy is not installed (.venv/bin/pip install py-spy)'}
    raw = os.path.join(out, name + '.pyspy.txt')
    cmd = [exe, 'record', '--nonblocking', '--threads', '-r', '200', '-d', str(int(math.ceil(seconds))), '-p', str(pid),
           '-f', 'raw', '-o', raw]
    if os.path.exists(raw):
        os.remove(raw)  # a file left by an earlier run must not stand for this one
    run = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=seconds + 60)
    # py-spy 0.4 may panic while it shuts its sampler down, after it wrote the samples: those still count
    if not os.path.exists(raw) or os.path.getsize(raw) == 0:
        return {'available': False, 'why': 'py-spy failed: %s' % run.stdout.decode(errors='replace')[-300:]}
    return dict(summarize_stacks(raw, 'MainThread'), available=True, tool='py-spy', raw=os.path.basename(raw))


def summarize_stacks(path, thread):
    """py-spy raw (collapsed) stacks -> shares of the thread's samples by leaf and by frame."""
    leaf, inclusive, total = {}, {}, 0
    # py-spy writes names as it reads them from the process's memory: a frame caught mid-change can carry bytes
    # that are not UTF-8 (once 0xf6 in a speed run, which then failed); such a name is kept, its bad bytes replaced
    with open(path, encoding='utf-8', errors='replace') as f:
        for line in f:
            stack, _, n = line.rstrip('\n').rpartition(' ')
            frames = stack.split(';')
            if thread not in frames[0]:
                continue
            n = int(n)
            total += n
            name = _frame_name(frames[-1])
            leaf[name] = leaf.get(name, 0) + n
            for fr in set(_frame_name(x) for x in frames[1:]):
                inclusive[fr] = inclusive.get(fr, 0) + n
    top = lambda d, k: [(name, round(100.0 * v / total, 1)) for name, v in sorted(d.items(), key=lambda x: -x[1])[:k]]
    return {'samples': total, 'self_pct': top(leaf, 12) if total else [],
            'inclusive_pct': [x for x in top(inclusive, 40) if 'racebot_sim_bridge' in x[0] or 'rospy' in x[0]][:15]
            if total else []}


def _frame_name(frame):
    """'Simulator.step (racebot_sim_bridge/engine/simulator.py:184)'
    -> 'Simulator.step (racebot_sim_bridge/engine/simulator.py)'."""
    name, _, where = frame.partition(' (')
    return '%s (%s)' % (name, where.rsplit(':', 1)[0]) if where else name

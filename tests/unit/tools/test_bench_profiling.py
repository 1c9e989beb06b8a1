"""The bench's py-spy summary (tools/bench/profiling.py): shares of the update loop's samples by frame, from py-spy's
raw (collapsed) stacks. No py-spy run: stacks written here."""

from bench import profiling

STEP = b'step (racebot_sim_bridge/engine/simulator.py:231)'
PHYSICS = b'step (racebot_sim_bridge/engine/physics.py:613)'


def test_shares_by_leaf_and_by_frame_of_the_threads_samples_only(tmp_path):
    raw = tmp_path / 'raw.txt'
    raw.write_bytes(b'thread (1): MainThread;main (racebot_sim_bridge/world_server.py:9);' + STEP + b';' + PHYSICS
                    + b' 3\nthread (1): MainThread;main (racebot_sim_bridge/world_server.py:9);' + STEP + b' 1\n'
                    + b'thread (2): writer;run (threading.py:975) 50\n')
    summary = profiling.summarize_stacks(str(raw), 'MainThread')
    assert summary['samples'] == 4  # the writer thread's 50 are not the loop's
    assert summary['self_pct'] == [('step (racebot_sim_bridge/engine/physics.py)', 75.0),
                                   ('step (racebot_sim_bridge/engine/simulator.py)', 25.0)]
    assert ('step (racebot_sim_bridge/engine/simulator.py)', 100.0) in summary['inclusive_pct']


def test_a_name_py_spy_read_half_changed_is_kept_with_its_bad_bytes_replaced(tmp_path):
    # a non-UTF-8 byte (0xf6) in a frame name once failed a whole speed run
    raw = tmp_path / 'raw.txt'
    raw.write_bytes(b'thread (1): MainThread;' + STEP + b';se\xf6nd (racebot_sim_bridge/x.py:1) 2\n'
                    b'thread (1): MainThread;' + STEP + b' 2\n')
    summary = profiling.summarize_stacks(str(raw), 'MainThread')
    assert summary['samples'] == 4
    assert ('se\ufffdnd (racebot_sim_bridge/x.py)', 50.0) in summary['self_pct']

"""The section "Reproduce": the commands that remake the report."""


def reproduce_section(stress, perf):
    lines = []
    w = lines.append
    w("## Reproduce")
    w("")
    w("```")
    w("./run study                      # records, replays, writes report/out/, draws this report")
    w("build/graspcd study --help       # options: --quick, --repeats, --shard i/n, --merge")
    if stress is not None:
        w("build/graspcd stress --help      # the stress suite: classes, columns, --seed, --cases")
    if perf is not None:
        w("./run perf                       # graspcd against FCL and MuJoCo: report/out/perf.json")
    w("```")
    w("")
    return lines

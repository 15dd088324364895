"""One working example per subcommand, shown as the last lines of its
``--help`` (run from the repository's root: the paths are those of
``models/`` and ``tests/data/references/``).  ``tests/test_help_examples.py``
runs every one of them, in this order, in a plain clone (a server, such as
``explore``, until it serves, then it is stopped with Ctrl-C)."""
import argparse

EXAMPLES = {
    "simulate": "acausal2d simulate models/pendulum.py --stop-time 2 --result-format mat "
                "--out out/pendulum",
    "check": "acausal2d check models/piston_engine.py",
    "params": "acausal2d params models/pendulum.py",
    "compare": "acausal2d compare out/pendulum/result.mat tests/data/references/Pendulum.csv "
               "--until 2 --out out/pendulum/compare",
    "sweep": "acausal2d sweep models/pulley_block.py --vary U1.mu,L2.mu,U3.mu,L4.mu=0:0.5:3 "
             "--outputs rope1.F --stop-time 1 --out out/sweep",
    "study": "acausal2d study models/pulley_block.py --list",
    "fit": "acausal2d fit models/pulley_block.py --data models/pulley_block_measured.csv "
           "--free U1.mu,L2.mu,U3.mu,L4.mu=0.1:0:0.6 --out out/fit",
    "optimize": "acausal2d optimize models/pendulum.py --vary body.m=1:0.5:2 "
                "--objective \"max(abs(revolute.w))\" --stop-time 1 --out out/opt",
    "linearize": "acausal2d linearize models/pendulum.py --equilibrium --out out/lin",
    "modes": "acausal2d modes models/pendulum.py --equilibrium --out out/modes",
    "export-fmu": "acausal2d export-fmu models/pendulum.py --kind cs --out out/Pendulum.fmu",
    "explore": "acausal2d explore models/piston_engine.py --port 8765",
    "cache": "acausal2d cache list",
    "diagram": "acausal2d diagram models/compressor.py --out out/compressor.svg",
}
"""Subcommand -> its example command line."""


def add_examples(sub):
    """Give every subparser of ``sub`` (an argparse subparsers action) its
    example as the epilog (kept where a command set its own)."""
    for name, parser in sub.choices.items():
        if parser.epilog is None and name in EXAMPLES:
            parser.epilog = "example:\n  " + EXAMPLES[name]
            parser.formatter_class = argparse.RawDescriptionHelpFormatter

"""Command-line entry point: ``python -m meshregrid <command> ...``.

Each module in ``meshregrid.commands`` adds one subcommand: it defines
``NAME``, ``HELP``, ``add_arguments(parser)`` and ``run(args) -> int``.
"""
import argparse
import importlib
import pkgutil
import sys

from . import commands


def _command_modules():
    for info in sorted(pkgutil.iter_modules(commands.__path__), key=lambda i: i.name):
        if not info.name.startswith("_"):
            yield importlib.import_module(f"{commands.__name__}.{info.name}")


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="meshregrid",
        description="Regrid surface triangulations with the MeshRegrid MeshLab filters (via PyMeshLab).")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for module in _command_modules():
        p = sub.add_parser(module.NAME, help=module.HELP, description=module.HELP)
        module.add_arguments(p)
        p.set_defaults(_run=module.run)
    return parser


def main(argv=None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "_run", None):
        parser.print_help()
        return 2
    import pymeshlab
    try:
        return int(args._run(args) or 0)
    except pymeshlab.PyMeshLabException as e:
        print(f"meshregrid {args.command}: {e}", file=sys.stderr)
        return 1

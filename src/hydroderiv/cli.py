"""Command line: ``hydroderiv <step> ...``, one subcommand per pipeline step."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from rich.console import Console
from rich.table import Table

from .errors import HydroderivError
from .geometry import CONFIGURATIONS, Body, load_user_body, suboff_body
from .geometry.suboff import CONFIGURATION_TITLES

console = Console()


def _print_body(body: Body, written: tuple[Path, ...] = ()) -> None:
    table = Table(title=body.name, show_header=False)
    table.add_column("quantity", style="bold")
    table.add_column("value")
    for quantity, value in body.summary():
        table.add_row(quantity, value)
    for name, area in body.component_areas().items():
        table.add_row(f"  wetted area, {name}", f"{area:.4f} m^2")
    for path in written:
        table.add_row("written", str(path))
    console.print(table)


def _geometry(args: argparse.Namespace) -> int:
    if args.stl:
        if args.length is None or args.moment_centre is None:
            raise HydroderivError("--stl needs --length (reference length, m) and --moment-centre X Y Z (m, file coordinates)")
        bodies = [load_user_body(args.stl, args.length, tuple(args.moment_centre), name=args.name)]
        outs = [Path(args.out)]
    else:
        configs = list(CONFIGURATIONS) if args.config.lower() == "all" else [args.config]
        bodies = [suboff_body(c, resolution=args.resolution) for c in configs]
        many = len(bodies) > 1
        outs = [Path(args.out) / c.upper() if many else Path(args.out) for c in configs]
    for body, out in zip(bodies, outs):
        written = body.write(out)
        _print_body(body, written)
    return 0


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="hydroderiv",
        description="Manoeuvring derivatives of underwater vehicles from RANS CFD (hybrid reference frames).",
    )
    steps = parser.add_subparsers(dest="step", required=True, metavar="STEP")

    geo = steps.add_parser(
        "geometry",
        help="write a body's surface (STL, one solid per component) and its reference quantities",
        description="Write body.stl and body.json to --out. Axes: origin at the moment centre, x forward, "
        "y starboard, z down, metres.",
    )
    titles = "; ".join(f"{k}: {v}" for k, v in CONFIGURATION_TITLES.items())
    geo.add_argument("--config", default="AFF-8", help=f"SUBOFF configuration, or 'all' ({titles})")
    geo.add_argument("--resolution", type=float, default=0.02, help="target surface edge length, m (default 0.02)")
    geo.add_argument("--stl", help="your own closed STL in metres (x forward, y starboard, z down) instead of SUBOFF")
    geo.add_argument("--length", type=float, help="reference length L of the prime system, m (with --stl)")
    geo.add_argument("--moment-centre", type=float, nargs=3, metavar=("X", "Y", "Z"), help="moment centre in the STL's coordinates, m")
    geo.add_argument("--name", help="name of the body (with --stl; default: the file name)")
    geo.add_argument("--out", required=True, help="output directory")
    geo.set_defaults(func=_geometry)
    return parser


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    try:
        return args.func(args)
    except HydroderivError as error:
        console.print(f"[bold red]error:[/] {error}", highlight=False)
        return 2


if __name__ == "__main__":
    sys.exit(main())

"""python3 -m posekit SUBCOMMAND ...: the posekit command-line tool."""

import subprocess
import sys

from ._cli_path import CLI_PATH


def main() -> int:
    try:
        return subprocess.call([CLI_PATH] + sys.argv[1:])
    except FileNotFoundError:
        print(f"posekit: error: {CLI_PATH}: the command-line tool is not there", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())

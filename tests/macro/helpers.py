"""In-process CLI runner: the same ``main()`` as the console script, without a new interpreter."""

from tribolmp.cli import main


class InProcess:
    def __init__(self, code, out, err):
        self.returncode, self.stdout, self.stderr = code, out, err


def run_main(capsys, *args):
    """Run ``tribolmp ARGS`` through :func:`tribolmp.cli.main`.

    Returns an object like the ``cli`` fixture's.
    """
    capsys.readouterr()
    code = main([str(a) for a in args])
    cap = capsys.readouterr()
    return InProcess(code, cap.out, cap.err)

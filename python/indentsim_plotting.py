"""Shared parts of the plot scripts: a matplotlib that writes files only, and the writing of a
figure with a clear message when the file cannot be written.

scripts/install_dependencies.sh installs Debian's python3-matplotlib and python3-numpy for
/usr/bin/python3; another python3 first on PATH (pyenv, conda, venv) may lack them. Then the
calling script is re-executed once with the system interpreter.
"""
import os
import sys


def ensure_matplotlib(script_name):
    """Imports matplotlib with the Agg backend, re-executing the script with /usr/bin/python3
    if this interpreter lacks it; exits with a clear message if neither has it."""
    try:
        import matplotlib
    except ImportError:
        system_python = "/usr/bin/python3"
        if os.environ.get("INDENTSIM_PLOT_REEXEC") != "1" and os.path.exists(system_python) \
                and os.path.realpath(sys.executable) != os.path.realpath(system_python):
            os.environ["INDENTSIM_PLOT_REEXEC"] = "1"
            os.execv(system_python, [system_python] + sys.argv)
        sys.exit(f"{script_name}: matplotlib is not installed for this Python "
                 f"({sys.executable}); run scripts/install_dependencies.sh")
    matplotlib.use("Agg")  # files only, never a display


def save_figure(figure, output, script_name, **savefig_options):
    """Lays the figure out and writes it to `output`; prints "wrote OUTPUT" and returns 0, or
    names the file and the reason on stderr and returns 1 (the scripts' exit status)."""
    figure.tight_layout()
    try:
        figure.savefig(output, **savefig_options)
    except OSError as error:
        print(f"{script_name}: cannot write {output}: {error}", file=sys.stderr)
        return 1
    print(f"wrote {output}")
    return 0

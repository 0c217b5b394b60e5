# SPDX-License-Identifier: BSD-3-Clause
"""How the Python tools write their outputs: never over one of their inputs, and whole or not at all.

- refuse_inputs(tool, outputs, inputs): exits with status 2 (bad usage, as argparse does) before
  anything is written when an output is the same file as an input (the same path, a symbolic link
  to it, or a hard link) or two outputs are the same file. The message names both.
- whole_file(path, mode): a file object on a temporary file beside path, renamed over path when the
  block ends without an exception and removed when it raises: a reader sees the earlier file or the
  new one, never a part. write_whole(path, data) writes str or bytes that way; save_figure(fig,
  path) saves a matplotlib figure that way, in the format its extension names.
- refuse_inside(tool, folders, inputs): the same status when an input lies in an output folder a
  run replaces; refuse_figure_formats(tool, outputs): when a figure's extension is not a format
  matplotlib writes.
- remove_earlier(tool, folder, patterns, written): a tool that writes a folder of outputs removes
  its own earlier outputs (the names matching patterns) that this run did not write again, so that
  a figure of an earlier run is not left looking current beside the new ones.

An output that is a symbolic link (not to an input) is replaced by the new file; its target is left
alone. The temporary is named .<name>.<random>.part in the output's folder (the same file system, so
that the rename is atomic).
"""

import contextlib
import fnmatch
import os
import stat
import sys
import tempfile

USAGE_STATUS = 2  # the tools' status for bad usage (argparse's), not for a run that failed


def same_file(a, b):
    """True when paths a and b name the same file: both exist and are one file (through symbolic or
    hard links), or neither needs to exist and they resolve to the same path."""
    if os.path.exists(a) and os.path.exists(b):
        return os.path.samefile(a, b)
    return os.path.realpath(a) == os.path.realpath(b)


def clash(outputs, inputs):
    """(what, output, other) for the first output that is an input or another output, else None.
    outputs: {what: path} (what: the flag or argument that names it, e.g. "--out") or a list of
    paths (each then called "output"); inputs: paths.
    None paths are skipped (an optional output not asked for)."""
    pairs = outputs.items() if isinstance(outputs, dict) else (("output", path) for path in outputs)
    named = [(what, path) for what, path in pairs if path is not None]
    for what, path in named:
        for other in inputs:
            if other is not None and same_file(path, other):
                return what, path, "its input %s" % other
    for i, (what, path) in enumerate(named):
        for other_what, other in named[i + 1:]:
            if same_file(path, other):
                return what, path, "its output %s %s" % (other_what, other)
    return None


def refuse_inputs(tool, outputs, inputs):
    """Exits with USAGE_STATUS, naming the files, when clash(outputs, inputs) finds one."""
    found = clash(outputs, inputs)
    if found is not None:
        what, path, other = found
        print("%s: %s %s is the same file as %s: refusing to write over it (name another output)"
              % (tool, what, path, other), file=sys.stderr)
        sys.exit(USAGE_STATUS)


def files_under(folder, suffixes):
    """The files below folder (at any depth) whose names end with one of suffixes: the inputs of a
    tool that reads a simulator's output folder, for refuse_inputs."""
    found = []
    for d, _, names in os.walk(folder):
        found += [os.path.join(d, n) for n in names if n.endswith(tuple(suffixes))]
    return found


def refuse_inside(tool, folders, inputs):
    """Exits with USAGE_STATUS when an input lies inside one of folders ({what: folder}), folders
    the tool's runs replace as a whole (an input there would be gone or stale after the run)."""
    for what, folder in folders.items():
        top = os.path.realpath(folder)
        for path in inputs:
            if os.path.commonpath([top, os.path.realpath(path)]) == top:
                print("%s: %s %s holds its input %s: refusing to replace it (move the input out)"
                      % (tool, what, folder, path), file=sys.stderr)
                sys.exit(USAGE_STATUS)


def refuse_figure_formats(tool, outputs):
    """Exits with USAGE_STATUS when an output figure ({what: path}, None skipped) has an extension
    matplotlib does not write, before any output is written (else the run would stop half done)."""
    asked = {what: path for what, path in outputs.items() if path is not None}
    if not asked:
        return  # no figure asked for: matplotlib is not needed
    from matplotlib.backend_bases import FigureCanvasBase
    known = FigureCanvasBase.get_supported_filetypes()
    for what, path in asked.items():
        if figure_format(path) not in known:
            print("%s: %s %s: matplotlib writes no .%s figure (%s)"
                  % (tool, what, path, figure_format(path), ", ".join(sorted(known))), file=sys.stderr)
            sys.exit(USAGE_STATUS)


def _new_mode(path):
    """The permissions of the file replaced, or those a new file gets (0666 less the umask)."""
    try:
        return stat.S_IMODE(os.stat(path).st_mode)
    except OSError:
        umask = os.umask(0)
        os.umask(umask)
        return 0o666 & ~umask


@contextlib.contextmanager
def whole_file(path, mode="w", **open_args):
    """A file object ("w" or "wb") whose content replaces path when the block ends; on an exception
    (SystemExit and KeyboardInterrupt included) the temporary is removed and path left as it was."""
    if mode not in ("w", "wb"):
        raise ValueError("whole_file: mode %r (only w and wb write a whole file)" % mode)
    folder = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix="." + os.path.basename(path) + ".", suffix=".part", dir=folder)
    try:
        with os.fdopen(fd, mode, **open_args) as f:
            yield f
        os.chmod(tmp, _new_mode(path))
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        raise


def write_whole(path, data):
    """Writes data (str or bytes) to path whole (whole_file)."""
    with whole_file(path, "wb" if isinstance(data, (bytes, bytearray)) else "w") as f:
        f.write(data)


def figure_format(path):
    """The savefig format of path's extension ("png" for a.png); png when it has none."""
    ext = os.path.splitext(path)[1]
    return ext[1:].lower() if ext else "png"


def save_figure(fig, path, **savefig_args):
    """Saves fig to path whole (whole_file), the format given by path's extension."""
    with whole_file(path, "wb") as f:
        fig.savefig(f, format=figure_format(path), **savefig_args)


def remove_earlier(tool, folder, patterns, written):
    """Removes the files of folder whose names match one of patterns (fnmatch: the names this tool
    writes there) and that are not in written (the paths this run wrote); returns their paths."""
    kept = {os.path.realpath(p) for p in written}
    removed = []
    if not os.path.isdir(folder):
        return removed
    for name in sorted(os.listdir(folder)):
        path = os.path.join(folder, name)
        if (any(fnmatch.fnmatchcase(name, p) for p in patterns) and os.path.realpath(path) not in kept
                and (os.path.isfile(path) or os.path.islink(path))):
            os.unlink(path)
            removed.append(path)
            print("%s: removed %s (an earlier run's output this run did not write)" % (tool, path),
                  file=sys.stderr)
    return removed

"""Writing a figure into an experiment's results folder: shared by the plot scripts beside it."""
import os
import tempfile


def save_figure(fig, figures, name, **savefig_options):
    """Writes FIGURES/NAME through a fresh temporary file renamed over it: a link or file planted
    under the name is replaced, never written through, and a failure leaves no part of a figure."""
    fd, temporary = tempfile.mkstemp(dir=figures, prefix="." + name + ".tmp-", suffix=os.path.splitext(name)[1])
    os.close(fd)
    try:
        # mkstemp makes the file readable by its owner alone; a figure gets the umask's mode, as
        # every other file omnicam writes.
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(temporary, 0o666 & ~umask)
        fig.savefig(temporary, **savefig_options)
        os.replace(temporary, os.path.join(figures, name))
    except BaseException:
        os.unlink(temporary)
        raise

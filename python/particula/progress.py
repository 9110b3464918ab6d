"""Progress of particula.run_case, particula.resume and Simulation.run_to: a callable told
(time, t_end, step) every quarter second of wall time and after the last step, or a progress bar
(tqdm when it is installed, else a line rewritten on standard error)."""
import os
import sys


class _Bar:
    """progress=True: a tqdm bar over simulated time, or a plain line without tqdm."""

    def __init__(self, label, stream):
        self.label = label
        self.stream = stream
        self.bar = None
        try:
            from tqdm.auto import tqdm
            self.tqdm = tqdm
        except ImportError:
            self.tqdm = None

    def __call__(self, time, t_end, step):
        if self.tqdm is not None:
            if self.bar is None:
                self.bar = self.tqdm(total=t_end, desc=self.label, unit="s", file=self.stream,
                                     bar_format="{desc}: {percentage:3.0f}%|{bar}| t = {n:.4g} / {total:.4g} s "
                                                "[{elapsed}<{remaining}]{postfix}")
            self.bar.n = min(time, t_end)
            self.bar.set_postfix_str("step %d" % step, refresh=False)
            self.bar.refresh()
        else:
            share = 100.0 * time / t_end if t_end > 0 else 100.0
            self.stream.write("\r%s: t = %.6g / %.6g s (%3.0f %%), step %d" % (self.label, time, t_end, share, step))
            self.stream.flush()
        self.shown = True

    def close(self):
        if self.bar is not None:
            self.bar.close()
        elif getattr(self, "shown", False):
            self.stream.write("\n")
            self.stream.flush()


class Progress:
    """What `progress=` asks for, as a callable for the solver (None for nothing), closed after
    the run. stream: where a bar is drawn (default: standard error)."""

    def __init__(self, progress, label, stream=None):
        self._bar = None
        self._own_stream = None
        if progress is None or progress is False:
            self.callback = None
        elif progress is True:
            if stream is None:
                stream = sys.stderr
            self._bar = _Bar(label, stream)
            self.callback = self._bar
        elif callable(progress):
            self.callback = progress
        else:
            raise TypeError("progress: True (a progress bar), False/None or a callable(time, t_end, step), not %r"
                            % (progress,))

    @classmethod
    def beside_captured_stderr(cls, progress, label):
        """For run_case and resume, whose standard error (file descriptor 2) is captured while
        they run: a bar is drawn on a duplicate of it taken now, which the capture leaves alone."""
        if progress is not True:
            return cls(progress, label)
        stream = os.fdopen(os.dup(2), "w")
        self = cls(progress, label, stream)
        self._own_stream = stream
        return self

    def close(self):
        if self._bar is not None:
            self._bar.close()
        if self._own_stream is not None:
            self._own_stream.close()

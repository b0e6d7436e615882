"""pytest plugin for `make nbval`: run each cell with ``store_history=True``, as Jupyter does.

nbval 0.11 executes cells with ``store_history=False``. IPython then cannot see the cell it is
running when it decides whether a trailing ``;`` silences the last expression (it reads the
input history), so ``ax.plot(x, y);`` would print ``[<matplotlib.lines.Line2D at 0x...>]``
under nbval but not in Jupyter, nbclient or the stored notebook. With the history stored, nbval
reproduces exactly what a reader's Jupyter shows. Nothing else changes (execution counts are
not compared by nbval).

Loaded with ``-p tools.nbval_jupyter_history`` (``python -m pytest`` from the repository root;
see the Makefile).
"""

from __future__ import annotations


def pytest_configure(config):
    from nbval.kernel import RunningKernel

    def execute_cell_input(self, cell_input, allow_stdin=None):
        return self.kc.execute(cell_input, store_history=True, allow_stdin=allow_stdin,
                               stop_on_error=False)

    RunningKernel.execute_cell_input = execute_cell_input

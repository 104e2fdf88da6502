"""The test bench: systems whose coupling is known, and the simulated backlash sweep.

Nothing in the library imports this package; the tests, the benchmarks and the
``backlash-report`` command do.

==================  ==========================================================================
module              what it holds
==================  ==========================================================================
``systems``         seeded coupled test systems whose coupling is known (NumPy only)
``sweep``           the backlash sweep on the simulated axis: indicators per trial, their
                    scores, the calibration the diagnosis ships (``diagnosis/calibration.json``)
``sweep_report``    the sweep's HTML report
==================  ==========================================================================
"""

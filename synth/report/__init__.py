"""What synth shows a person: the terminal view, the HTML design report, its PDF, its graphs, progress bars.

* :mod:`synth.report.text` - the terminal view of a Result (every scene prints it);
* :mod:`synth.report.html` - the HTML report (digest first) and the notebook digest (``Result._repr_html_``);
* :mod:`synth.report.pdf` - the report as PDF (WeasyPrint, else headless Chromium);
* :mod:`synth.report.plots` - the thesis's graphs, drawn from the evaluator's numbers;
* :mod:`synth.report.progress` - progress bars (terminal, ``tqdm.auto`` in Jupyter).

Nothing is imported here: ``import synth.report.progress`` stays light.
"""

__all__: list = []

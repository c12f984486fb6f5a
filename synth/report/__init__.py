"""What synth shows a person: the terminal view, the HTML design report, its PDF, its graphs.

* :mod:`synth.report.text` - the terminal view of a Result (every scene prints it);
* :mod:`synth.report.html` - the HTML report (digest first) and the notebook digest (``Result._repr_html_``);
* :mod:`synth.report.pdf` - the report as PDF (WeasyPrint, else headless Chromium);
* :mod:`synth.report.plots` - the thesis's graphs, drawn from the evaluator's numbers;

Nothing is imported here. The progress bars are :mod:`synth.progress` (below the engines that draw them).
"""

__all__: list = []

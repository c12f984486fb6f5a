"""Should-cost of a tensioner: every part's price with its source, what it is and its band.

* :mod:`synth.cost.prices`: the price file (``catalogs/prices.csv`` and a company's own ``prices.csv``);
* :mod:`synth.cost.bought`: bought-in parts (bearings, bolts) by relations fitted to public price lists;
* :mod:`synth.cost.made`: made parts (springs, moulded elements, bushings) by material mass and process terms;
* :mod:`synth.cost.book`: the price book of a catalog setting at an annual volume;
* :mod:`synth.cost.columns`: the design space's cost columns (what the optimiser reads), from the book;
* :mod:`synth.cost.breakdown`: a design's price lines (quoted, modelled or assumed);
* :mod:`synth.cost.decision`: how much the cheapest design depends on the prices (probability, ranges).

The package imports nothing at its top, so that the design space can import :mod:`synth.cost.columns`
without running the modules that import the optimiser.
"""

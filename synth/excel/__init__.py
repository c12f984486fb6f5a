"""The engineer's Excel workflow: input template, workbook reader, results workbook.

* :mod:`synth.excel.template`: ``synth template FILE.xlsx`` writes the design
  input workbook in the thesis's shape (Fig. 22-26), built from
  :data:`synth.schema.FIELDS`;
* :mod:`synth.excel.reader`: reads a filled workbook into the mapping that
  :func:`synth.schema.validate` takes, with problems pointing to the cell;
* :mod:`synth.excel.results_workbook`: the results workbook (output table of Tables
  10/14 with verdict colours, echo of the data read, suggested corrections,
  one sheet per scene result).
"""

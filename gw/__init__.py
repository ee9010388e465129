"""Greenwood-Williamson rough-surface integration (eqs. 20-28) of any asperity law.

Not implemented yet: it is a later stage of the roadmap. It will consume
`fem_asperity.closed_forms.laws.AsperityLaws` (the paper's constants or refitted ones) or tabulated FE curves.
"""

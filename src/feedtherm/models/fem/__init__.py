"""The finite element core: linear heat conduction on P1 tetrahedra with scikit-fem.

Modules, one job each:

- :mod:`.topology` -- join meshes without merging nodes, split a conforming mesh along an
  interface (duplicate its nodes), find a part's facets.
- :mod:`.meshes` -- small structured tetrahedral meshes (boxes, bars, two blocks, a rod with a
  slider) for tests and examples.
- :mod:`.heat` -- assembly (conduction, capacity, convection, sources), steady solve and
  theta-method time stepping with factorised matrices.
- :mod:`.layers` -- a surface cut into regular axial layers: per-layer loads and convection
  terms for a heat band or a covered strip that moves layer by layer.
- :mod:`.interfaces` -- thermal contact resistance between parts that do not share nodes, and
  the sliding interface whose moves are index shifts.
- :mod:`.energy` -- the energy balance from separate integrals, not from the solver's matrices.
- :mod:`.fields` -- reading a field: section means along an axis, values at points.

See ``docs/fem-core.md``.
"""

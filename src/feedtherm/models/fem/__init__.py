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

The bench model (a whole feed system) on top of the core:

- :mod:`.geometry` -- each part meshed with gmsh at a density, cached on disk.
- :mod:`.facets` -- boundary triangles, surface quadrature, closest points on triangles.
- :mod:`.faces` -- the facets of a declared surface (box and cylinder face selectors).
- :mod:`.coupling` -- the non-conforming interface conductance of a joint (fixed or sliding).
- :mod:`.readout` -- sensors at points, the screw's section means, part means.
- :mod:`.bench` -- :class:`~.bench.FemDiscretization`, the interface the shared integrator uses.

See ``docs/fem-core.md`` and ``docs/fem-model.md``.
"""

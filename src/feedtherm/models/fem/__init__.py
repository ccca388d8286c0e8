"""The finite element model of a feed system: linear tetrahedra, gmsh and scikit-fem.

Modules, one job each:

- :mod:`.geometry` -- each part meshed with gmsh at a density, cached on disk.
- :mod:`.conduction` -- the conduction matrix of linear tetrahedra.
- :mod:`.facets` -- boundary triangles, surface quadrature, closest points on triangles.
- :mod:`.faces` -- the facets of a declared surface (box and cylinder face selectors).
- :mod:`.coupling` -- the non-conforming interface conductance of a joint (fixed or sliding).
- :mod:`.readout` -- sensors at points, the screw's section means, part means.
- :mod:`.bench` -- :class:`~.bench.FemDiscretization`, the model the shared integrator runs.

See ``docs/fem-model.md``; its verification cases are descriptions in
``tests/verification/cases/``.
"""

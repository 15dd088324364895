"""User tools on top of compiler and runtime: the compiled model
(:mod:`.compiled`), results (:mod:`.result`), structure report
(:mod:`.check`), reference comparison (:mod:`.compare`), plots
(:mod:`.plotting`), animation (:mod:`.scene`, :mod:`.animation`), model
loading (:mod:`.loader`), parameter studies on Dask (:mod:`.sweep`),
model-declared studies (:mod:`.study`), atomic file writes (:mod:`.files`)
and the command line (:mod:`.cli`)."""

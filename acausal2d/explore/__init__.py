"""``acausal2d explore``: a local web page on a warm compiled model.

Change a parameter and the model re-runs at once: the mechanism's animation
(the scene of ``simulate``'s animation.html), the model's figures and any
signal picked on the page update in place, the previous curve stays faint,
"Pin" keeps a run as a reference, and the parameter set exports as
``--set`` options or the run as CSV.  Dragging a joint at the first frame
moves the mechanism's start position (re-assembled and re-run).

:class:`~acausal2d.explore.runner.Explorer` holds the compiled model and the
run queue, :mod:`acausal2d.explore.requests` checks the JSON requests and
:mod:`acausal2d.explore.server` is the Starlette application (the JSON API
is described there).  The web server packages are the optional extra
``explore`` (``pip install 'acausal2d[explore]'``).
"""

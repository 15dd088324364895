"""The runtime: one simulation run (:mod:`.simulation`) with consistent
initialization (:mod:`.initialize`, :mod:`.newton`), IDA (:mod:`.ida`),
events (:mod:`.events`), state selection (:mod:`.selection`), singular
positions (:mod:`.singularities`, :mod:`.failure`) and consistent output
points (:mod:`.projection`)."""

"""The compiler: pure passes over one structural state
(:mod:`.structure`), run in order by :mod:`.pipeline` - :mod:`.flatten`,
:mod:`.relations`, :mod:`.balance`, :mod:`.aliases`, :mod:`.pantelides`,
:mod:`.always_states` - and the products they feed: the dummy-derivative
choice (:mod:`.dummy_derivatives`), the frozen :mod:`.system` and its
semi-explicit index-1 formulation (:mod:`.index1`)."""

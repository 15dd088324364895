"""The modelling language: components, parameters and variables
(:mod:`.dsl`), connectors (:mod:`.connectors`), the symbols of one
compilation (:mod:`.symbols`), connection sets (:mod:`.unionfind`) and what
component hooks may ask of the whole model (:mod:`.context`)."""

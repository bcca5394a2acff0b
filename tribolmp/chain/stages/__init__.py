"""The chain's stages, one file each (see :mod:`tribolmp.chain.stage` for the contract).

The order in which they run is the registry's, :mod:`tribolmp.chain.registry`;
this package imports nothing, so a stage's code closure never includes its
siblings.
"""

"""App-side (document) objects of VarSurf; no GUI imports here."""

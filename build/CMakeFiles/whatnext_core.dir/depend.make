# Empty dependencies file for whatnext_core.
# This may be replaced when dependencies are built.

# Empty dependencies file for whatnext_io.
# This may be replaced when dependencies are built.

# Empty dependencies file for whatnext.
# This may be replaced when dependencies are built.

file(REMOVE_RECURSE
  "libwhatnext_core.a"
)

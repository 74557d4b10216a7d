file(REMOVE_RECURSE
  "libwhatnext_io.a"
)

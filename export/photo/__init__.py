"""Photo measurement: marker sheets to print, and (with the ``measure`` extra) marker detection."""

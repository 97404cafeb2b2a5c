this is a text file, not NetCDF

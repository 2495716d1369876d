// placeholder: filled by the zonal work

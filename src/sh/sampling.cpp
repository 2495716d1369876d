// placeholder: filled by the sampling work

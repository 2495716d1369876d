// placeholder: filled by the rotation work

// placeholder: filled by the window work

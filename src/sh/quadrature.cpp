// placeholder: filled by the quadrature work

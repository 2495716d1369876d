// placeholder: filled by the eval_batch work

// placeholder: filled in this issue

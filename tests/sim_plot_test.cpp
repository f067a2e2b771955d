// placeholder: tests written in this issue

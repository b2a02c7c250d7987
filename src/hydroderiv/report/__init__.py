"""Reports: tables on the terminal and plots for the validation record."""

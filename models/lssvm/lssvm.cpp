// placeholder, replaced by the LS-SVM implementation

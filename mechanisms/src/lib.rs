//! The textbook cases of the validation manual as generated models.

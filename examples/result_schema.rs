fn main(){ print!("{}", contopt_results::schema_markdown()); }

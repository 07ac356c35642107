//! The PPM writer of the host examples: header, size and known pixels of a known drawing.

use crate::raster::Image;

#[test]
fn ppm_has_the_p6_header_the_size_and_the_drawn_pixels() {
    let (w, h) = (32, 20);
    let mut img = Image::new(w, h, [10, 20, 30]);
    // A red triangle covering the left half's middle, a nearer blue one over part of it.
    img.triangle(
        [[2.0, 2.0, 5.0], [20.0, 2.0, 5.0], [2.0, 18.0, 5.0]],
        [[255.0, 0.0, 0.0]; 3],
    );
    img.triangle(
        [[4.0, 4.0, 1.0], [10.0, 4.0, 1.0], [4.0, 10.0, 1.0]],
        [[0.0, 0.0, 255.0]; 3],
    );
    // A farther green one must stay hidden behind the red.
    img.triangle(
        [[3.0, 12.0, 9.0], [8.0, 12.0, 9.0], [3.0, 16.0, 9.0]],
        [[0.0, 255.0, 0.0]; 3],
    );
    img.line([0.0, 19.0], [31.0, 19.0], [255, 255, 255]);
    let ppm = img.to_ppm();
    let header = format!("P6\n{w} {h}\n255\n");
    assert!(ppm.starts_with(header.as_bytes()));
    assert_eq!(ppm.len(), header.len() + w * h * 3);
    let pixel = |x: usize, y: usize| {
        let i = header.len() + 3 * (y * w + x);
        [ppm[i], ppm[i + 1], ppm[i + 2]]
    };
    assert_eq!(pixel(30, 2), [10, 20, 30], "background");
    assert_eq!(pixel(12, 5), [255, 0, 0], "red triangle");
    assert_eq!(pixel(5, 5), [0, 0, 255], "the nearer triangle wins");
    assert_eq!(pixel(4, 13), [255, 0, 0], "the farther triangle is hidden");
    assert_eq!(pixel(17, 19), [255, 255, 255], "the line");
    assert_eq!(img.pixel(12, 5), [255, 0, 0]);
}
